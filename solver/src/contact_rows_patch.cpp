// The soft step's sliding patch on the wide rows (slide_patch.cpp says why), lane by lane: the
// scalar kernel on each lane's values, so the coloured and scalar sweeps keep the same bits.
#include <array>

#include "slide_patch.h"
#include "tumble/core/lane_kernel.h"
#include "tumble/solver/contact_rows.h"

namespace tumble {

// The soft step's patch of lane `lane`'s manifold (slide_patch.h), on the lanes' values:
// `solve` (slidePatch) on them, kept when it returns true.
template <class Solve>
bool ContactRows::onPatch(Bundle& bundle, int lane, std::span<const SolverBody> solverBodies,
                          Lane (&v)[2][6], Solve&& solve) {
    Point* const slots = points_.data() + bundle.firstPoint;
    const int count = bundle.points[lane];
    std::array<PatchPoint, 4> patch;
    for (int i = 0; i < count; ++i) {
        const Point& p = slots[i];
        PatchPoint& q = patch[i];
        q.normalImpulse = p.normalImpulse[lane];
        q.tangentImpulse = {p.tangentImpulse[0][lane], p.tangentImpulse[1][lane]};
        for (int r = 0; r < 2; ++r) {
            for (int k = 0; k < 3; ++k) {
                q.angularA[r](k) = p.tangentAngularA[r][k][lane];
                q.angularB[r](k) = p.tangentAngularB[r][k][lane];
                q.impulseA[r](k) = p.tangentImpulseA[r][k][lane];
                q.impulseB[r](k) = p.tangentImpulseB[r][k][lane];
            }
        }
    }
    PatchBodies bodies;
    for (int k = 0; k < 3; ++k) {
        bodies.linearA(k) = v[0][k][lane];
        bodies.angularA(k) = v[0][3 + k][lane];
        bodies.linearB(k) = v[1][k][lane];
        bodies.angularB(k) = v[1][3 + k][lane];
    }
    bodies.inverseMassA = bundle.inverseMassA[lane];
    bodies.inverseMassB = bundle.inverseMassB[lane];
    const Vec3 normal(bundle.normal[0][lane], bundle.normal[1][lane], bundle.normal[2][lane]);
    bodies.yawA = normal.dot(solverBodies[bundle.bodyA[lane]].inverseInertia * normal);
    bodies.yawB = normal.dot(solverBodies[bundle.bodyB[lane]].inverseInertia * normal);
    std::array<Vec3, 2> tangents;
    for (int r = 0; r < 2; ++r) {
        for (int k = 0; k < 3; ++k)
            tangents[r](k) = bundle.tangents[r][k][lane];
    }
    const std::array<Real, 2> target = {bundle.tangentTarget[0][lane],
                                        bundle.tangentTarget[1][lane]};
    if (!solve(bodies, normal, tangents, target, bundle.friction[lane],
               std::span<PatchPoint>(patch.data(), count)))
        return false;
    for (int k = 0; k < 3; ++k) {
        v[0][k][lane] = bodies.linearA(k);
        v[0][3 + k][lane] = bodies.angularA(k);
        v[1][k][lane] = bodies.linearB(k);
        v[1][3 + k][lane] = bodies.angularB(k);
    }
    for (int i = 0; i < count; ++i) {
        slots[i].tangentImpulse[0][lane] = patch[i].tangentImpulse[0];
        slots[i].tangentImpulse[1][lane] = patch[i].tangentImpulse[1];
    }
    return true;
}

// The lanes whose patch surely sticks (patchSticks, bit per lane): the sums of all four at once
// from the slots instead of onPatch's copy of their levers, a lane's slots past its points masked
// out by hasPoint. Lane by lane, the sums took 22 M instructions in pyramid-20's 0.5 s at 3 x 45;
// four at once in the lane kernel's copy, 7.8 M.
TUMBLE_LANE_KERNEL unsigned ContactRows::stickingPatches(const Bundle& bundle,
                                                         const Lane (&v)[2][6]) const {
    const Point* const slots = points_.data() + bundle.firstPoint;
    const auto masked = [](LaneMask m, Lane x) {
        return reinterpret_cast<Lane>(reinterpret_cast<LaneMask>(x) & m);
    };
    Lane total{};
    Lane old[2]{};
    Lane turn[2]{};  // sum N_i ((rB x t_k) . wB - (rA x t_k) . wA)
    for (int i = 0; i < bundle.maxPoints; ++i) {
        const Point& p = slots[i];
        const LaneMask has = bundle.hasPoint[i];
        const Lane n = masked(has, p.normalImpulse);
        total += n;
        for (int r = 0; r < 2; ++r) {
            old[r] += masked(has, p.tangentImpulse[r]);
            Lane lever{};
            for (int k = 0; k < 3; ++k) {
                lever +=
                    p.tangentAngularB[r][k] * v[1][3 + k] - p.tangentAngularA[r][k] * v[0][3 + k];
            }
            turn[r] += masked(has, n * lever);
        }
    }
    Lane slip[2];
    for (int r = 0; r < 2; ++r) {
        Lane linear{};
        for (int k = 0; k < 3; ++k)
            linear += bundle.tangents[r][k] * (v[1][k] - v[0][k]);
        slip[r] = (linear + turn[r] / total) - bundle.tangentTarget[r];
    }
    const Lane inverseMasses = bundle.inverseMassA + bundle.inverseMassB;
    unsigned sticking = 0;
    for (int lane = 0; lane < bundle.laneCount; ++lane) {
        sticking |=
            patchSticks(total[lane], {old[0][lane], old[1][lane]}, {slip[0][lane], slip[1][lane]},
                        inverseMasses[lane], bundle.friction[lane])
                ? 1u << lane
                : 0u;
    }
    return sticking;
}

unsigned ContactRows::slidePatches(Bundle& bundle, std::span<const SolverBody> solverBodies,
                                   const SolverSettings& settings, bool soft, unsigned only,
                                   Lane (&v)[2][6]) {
    const unsigned sticking = stickingPatches(bundle, v);
    unsigned slid = 0;
    for (int lane = 0; lane < bundle.laneCount; ++lane) {
        if (bundle.points[lane] < 2 || (soft && !bundle.normals[lane]) ||
            (only & (1u << lane)) == 0 || (sticking & (1u << lane)) != 0)
            continue;
        const bool on = onPatch(
            bundle, lane, solverBodies, v,
            [&](PatchBodies& bodies, const Vec3& normal, const std::array<Vec3, 2>& tangents,
                const std::array<Real, 2>& target, Real friction, std::span<PatchPoint> patch) {
                return slidePatch(bodies, normal, tangents, target, friction, settings.relaxation,
                                  patch);
            });
        slid |= on ? 1u << lane : 0u;
    }
    return slid;
}

}  // namespace tumble
