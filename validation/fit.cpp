#include <cmath>
#include <cstddef>

#include <Eigen/Dense>

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

double fitSlope(const std::vector<double>& x, const std::vector<double>& y) {
    const std::size_t n = x.size();
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < n; ++i) {
        sx += x[i];
        sy += y[i];
        sxx += x[i] * x[i];
        sxy += x[i] * y[i];
    }
    const double count = static_cast<double>(n);
    return (count * sxy - sx * sy) / (count * sxx - sx * sx);
}

double fitAcceleration(const std::vector<double>& t, const std::vector<double>& s) {
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < t.size(); ++i) {
        // Centre time for conditioning; the acceleration does not depend on the origin of t.
        const double tc = t[i] - 0.5 * (t.front() + t.back());
        const Eigen::Vector3d basis(1, tc, 0.5 * tc * tc);
        normal += basis * basis.transpose();
        rhs += basis * s[i];
    }
    return normal.ldlt().solve(rhs)(2);
}

}  // namespace tumble::validation
