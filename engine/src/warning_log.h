#pragma once
/// The world's warnings (tumble/warnings.h): a list of fixed capacity, so raising one inside a
/// step never allocates; causes past the capacity are counted, not kept.

#include <cstddef>
#include <vector>

#include "tumble/warnings.h"

namespace tumble {

class WarningLog {
public:
    static constexpr std::size_t kCapacity = 64;

    WarningLog() { items_.reserve(kCapacity); }

    /// Keeps `warning` unless one of the same kind and cause is already kept.
    void raise(const Warning& warning);
    /// A contact began or a joint was made between bodies of these inverse masses (1/kg; 0 for a
    /// static or kinematic body): raises MassRatio when both are dynamic and far apart.
    void checkMassRatio(BodyId a, double inverseMassA, BodyId b, double inverseMassB,
                        JointId joint = {});

    const std::vector<Warning>& items() const { return items_; }
    std::size_t dropped() const { return dropped_; }
    void clear() {
        items_.clear();
        dropped_ = 0;
    }

private:
    std::vector<Warning> items_;
    std::size_t dropped_ = 0;
};

}  // namespace tumble
