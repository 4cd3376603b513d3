#pragma once
/// What every stage of a step reads: the step length and the world-wide constants for this step.

#include "tumble/core/math.h"

namespace tumble {

struct StepContext {
    Real h = 0;         ///< step (s)
    Real inverseH = 0;  ///< 1/h (1/s)
    Vec3 gravity = Vec3::Zero();
};

}  // namespace tumble
