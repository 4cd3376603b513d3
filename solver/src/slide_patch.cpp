// Why the soft step's friction rows start from a patch (docs/ARCHITECTURE.md, "The soft step").
//
// A face that starts to slide needs mu N_i at each point, all along the slip. The points'
// coupled rows, one after the other, do not give that from a cold start in one sweep: each
// point's rim answer is its own disc's in its K metric, whose lever turns the body about the
// normal, and the next point meets that yaw as slip across the push. The default step sweeps
// twenty times and converges (1e-14); the soft step solves each substep's rows twice (biased,
// relax), and a pushed 1000 kg cube's friction in the substep it started to slide pointed up to
// 11 degrees off the slip and carried 1.3 % less than mu m g hs along it, 0.45 % of its step
// (3 x 45); the scatter then went into the cube's yaw and took steps to settle.
//
// The patch is the manifold's friction as one row at its centre of pressure c = sum N_i r_i /
// sum N_i, on the bodies' translation and their turn about the normal: the manifold's normal
// rows hold the tipping that the lever at c would add (with it, K took the cube's tip as give and
// the patch stuck where the face slides), and the turn about n, n' I^-1 n, is free (on
// translation alone a cube sticking on a turning platform near mu g read as sliding). When the slip
// at c needs more than mu sum N_i to stop, the face slides as a whole, and the answer on the rim
// split by N_i puts each point on its own rim along that slip: a fixed point of the points' rows
// that follow (the rim answer keeps an impulse whose slip it opposes). A face that sticks, or turns
// about its normal with no slip at c, is left to the points' rows as it was.
//
// The patch gives every point friction along one direction, so no torque about the normal: a face
// that slides and spins gets its turn's friction from the points' rows after the patch, each
// point's slip being the centre's plus the spin's. And the relax sweep's normal rows change the
// load: the rigid relax sweep carries what the soft biased one did not (a body sinking into its
// sag), and a face that starts to slide tips onto its leading edge. So the relax sweep solves a
// face whose patch slid in either sweep of the substep again after its normal rows, patch and
// points' rows, at the new loads (sweep_rows.cpp, contact_rows.cpp): the face's total is bounded
// by mu sum N_i, each point by its own disc (a lifted point keeps none). Before, the patch's sum
// was split again by the new normals, N_i / sum N each: bounded by the biased sweep's load, a
// cube kicked from zero depth took 0.98817 of mu m g h in step 1 (3 x 45), and the split, all
// along the sum, dropped the points' rows' torque: a cube sliding at 0.3 m/s and spinning at
// 1.5 rad/s kept its spin to 1e-5 for 40 steps while its centre circled (the default step stops
// it in 6).
#include "slide_patch.h"

#include <algorithm>

#include "contact_kernels.h"

namespace tumble {

namespace {

// Each point's friction to `share` of `patch` relaxed by omega, the changes on the bodies.
void setShares(PatchBodies& bodies, const std::array<Vec3, 2>& tangents,
               std::span<PatchPoint> points, const Eigen::Matrix<Real, 2, 1>& patch, Real total,
               Real omega) {
    using Vec2 = Eigen::Matrix<Real, 2, 1>;
    for (PatchPoint& p : points) {
        const Vec2 before(p.tangentImpulse[0], p.tangentImpulse[1]);
        const Vec2 next = before + omega * ((p.normalImpulse / total) * patch - before);
        const Vec2 delta = next - before;
        const Vec3 linear = delta.x() * tangents[0] + delta.y() * tangents[1];
        bodies.linearA -= bodies.inverseMassA * linear;
        bodies.angularA -= delta.x() * p.impulseA[0] + delta.y() * p.impulseA[1];
        bodies.linearB += bodies.inverseMassB * linear;
        bodies.angularB += delta.x() * p.impulseB[0] + delta.y() * p.impulseB[1];
        p.tangentImpulse = {next.x(), next.y()};
    }
}

}  // namespace

bool slidePatch(PatchBodies& bodies, const Vec3& normal, const std::array<Vec3, 2>& tangents,
                const std::array<Real, 2>& target, Real friction, Real omega,
                std::span<PatchPoint> points) {
    using Vec2 = Eigen::Matrix<Real, 2, 1>;
    Real total = 0;
    for (const PatchPoint& p : points)
        total += p.normalImpulse;
    if (!(total > 0 && friction > 0))
        return false;
    std::array<Vec3, 2> angularA{Vec3::Zero(), Vec3::Zero()};
    std::array<Vec3, 2> angularB = angularA;
    Vec2 old = Vec2::Zero();
    for (const PatchPoint& p : points) {
        const Real w = p.normalImpulse / total;
        for (int k = 0; k < 2; ++k) {
            angularA[k] += w * p.angularA[k];
            angularB[k] += w * p.angularB[k];
            old(k) += p.tangentImpulse[k];
        }
    }
    const Vec3 dv = bodies.linearB - bodies.linearA;
    Vec2 vt;
    for (int r = 0; r < 2; ++r) {
        vt(r) = ((tangents[r].dot(dv) + angularB[r].dot(bodies.angularB)) -
                 angularA[r].dot(bodies.angularA)) -
                target[r];
    }
    Eigen::Matrix<Real, 2, 2> k;
    for (int r = 0; r < 2; ++r) {
        for (int c = 0; c < 2; ++c) {
            k(r, c) = (r == c ? bodies.inverseMassA + bodies.inverseMassB : Real(0)) +
                      angularA[r].dot(normal) * angularA[c].dot(normal) * bodies.yawA +
                      angularB[r].dot(normal) * angularB[c].dot(normal) * bodies.yawB;
        }
    }
    DiscBlock disc;
    if (!disc.set(k))
        return false;
    const Vec2 b = k * old - vt;
    const Real radius = friction * total;
    if ((disc.inverse * b).squaredNorm() <= radius * radius)
        return false;  // sticks as a whole
    const Vec2 patch = solveDiscRim(disc, b, radius);
    setShares(bodies, tangents, points, patch, total, omega);
    return true;
}

}  // namespace tumble
