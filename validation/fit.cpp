#include <cmath>
#include <cstddef>

#include "case.h"

namespace tumble::validation {

double logLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
    const std::size_t n = x.size();
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double lx = std::log(x[i]);
        const double ly = std::log(y[i]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    const double count = static_cast<double>(n);
    return (count * sxy - sx * sy) / (count * sxx - sx * sx);
}

}  // namespace tumble::validation
