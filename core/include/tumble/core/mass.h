#pragma once
/// Mass properties: shared by collision/ (computed from geometry) and engine/ (bodies).

#include "tumble/core/math.h"

namespace tumble {

/// Mass, centre of mass and inertia of a body or shape, in its own frame.
struct MassProperties {
    Real mass = 1;                          ///< (kg), > 0 for a dynamic body
    Vec3 localCenter = Vec3::Zero();        ///< centre of mass in the local frame (m)
    Mat3 inertia = Mat3::Identity() * 0.4;  ///< about the centre of mass, local axes (kg m^2);
                                            ///< symmetric positive definite, principal moments
                                            ///< obeying the triangle inequality
};

}  // namespace tumble
