#include "anchor_table.h"

#include <algorithm>
#include <cmath>

#include "tumble/core/lane_kernel.h"

namespace tumble {
namespace {

// A manifold whose friction impulses add up to this share of mu sum(lambda_n) slips.
constexpr Real kSlipShare = 0.99;

Vec3 onPlane(const Vec3& v, const Vec3& n) {
    return v - v.dot(n) * n;
}

Real largest(const Vec3* drifts, int count) {
    Real most = 0;
    for (int i = 0; i < count; ++i)
        most = std::max(most, drifts[i].norm());
    return most;
}

// Whether anchors are stale: their separation now (`apart`, before this step's bend) is more
// than half the drift the pass was handed last step (`last`), which was over the deadband and
// within the catch-up, so the pass could have closed it in one step. It came back: the velocity
// solve and the push-out hold the bodies' rest shape elsewhere than the anchors, which were
// seated while it was another (a pile's landing sag), and kept they fought it every step.
// Slip is not that: a manifold that slips reaches its limit and is let go by release(). Nor is a
// drift that is back right after such a seat: the bodies move there, and the anchors are what
// holds them, so a manifold seated afresh as stale is not again until its drift was within the
// deadband. Re-seated whenever the drift came back, some 190 manifolds of the 5,000-body soak's
// pile stayed in the pass, 4-6 re-seated every step, and it never fell asleep (main: 9.43 s).
bool stale(Real last, Real apart, const AnchorLengths& lengths) {
    return apart > lengths.deadband && last > lengths.deadband && last <= lengths.catchUp &&
           apart > 0.5 * last;
}

}  // namespace

// The manifold's anchors are seated together: anchors seated at different times disagree with
// any rigid motion, and the friction rows then fought each other.
//
// Anchors measure slip only while they stay at the contact. A rolling body's contact point moves
// over both surfaces while nothing slips, and the material points it left part as a cycloid,
// R (t - sin t) for a ball of radius R rolled by R t: with anchors kept over 1 cm (1.7e-5 m at
// R = 0.1 m, above the deadband) the pass pulled a ball rolling down a slope and changed its
// acceleration by 4.2e-5 relative (validate.rolling-resistance, 28 steps of the pass). So a
// manifold whose points moved away from their anchors' midpoint by more than the anchors moved
// apart (twice that, plus the deadband) has rolled, and is seated afresh where its points are:
// its slip is then what the velocity solve left, the bend of the paths aside. A point
// sticking on a platform stays with its anchor on one body and leaves the other's by the
// drift, so it moves from their midpoint by half the drift and keeps them.
//
// The drift is the one expected at the end of the step: the points' paths bend with their
// bodies' spins, which velocities sticking at the start of the step do not follow (on a turning
// platform a point falls behind a straight line by omega^2 r h^2 / 2 per step: 0.46 mm at the
// issue's slip speed).
//
// driftsOf: drifts() on its entry. Compiled for AVX2 and the baseline like the solver's kernels
// (lane_kernel.h, the same bits): the baseline's two-operand SSE2 copied every temporary of the
// rotations and projections through extra registers (4.3 % of pyramid-20's instructions).
TUMBLE_LANE_KERNEL void AnchorTable::driftsOf(Entry& entry, std::uint64_t solve,
                                              const Contact& contact, const BodyMotion& a,
                                              const BodyMotion& b, Real h,
                                              const ContactConstraint& c,
                                              const AnchorLengths& lengths, bool reseatStale,
                                              Vec3* drifts) {
    const Vec3& n = c.normal;
    bool seat = entry.solve + 1 != solve || entry.count == 0;
    entry.solve = solve;
    Entry kept = entry;  // the anchors in this step's point order
    Real apart = 0;      // largest(drifts, c.pointCount) once every point kept its anchors
    for (int i = 0; i < c.pointCount && !seat; ++i) {
        const std::uint32_t feature = contact.manifold.points[i].featureId;
        int k = 0;
        while (k < entry.count && entry.feature[k] != feature)
            ++k;
        if (k == entry.count) {
            seat = true;
            break;
        }
        kept.onA[i] = entry.onA[k];
        kept.onB[i] = entry.onB[k];
        kept.feature[i] = feature;
        const Vec3 onA = a.center + a.orientation * entry.onA[k];
        const Vec3 onB = b.center + b.orientation * entry.onB[k];
        const Real away =
            onPlane(0.5 * (onA + onB) - contact.manifold.points[i].position, n).norm();
        drifts[i] = onPlane(onB - onA, n);
        if (away >= lengths.reach) {
            seat = true;
            break;
        }
        const Real drift = drifts[i].norm();
        apart = std::max(apart, drift);
        seat = away > lengths.deadband + 2 * drift;
    }
    bool reseated = false;
    if (!seat && reseatStale) {
        kept.reseated = kept.reseated && apart > lengths.deadband;
        reseated = !kept.reseated && stale(entry.drift, apart, lengths);
        seat = reseated;
    }
    if (seat) {
        kept.reseated = reseated;
        for (int i = 0; i < c.pointCount; ++i) {
            const Vec3& point = contact.manifold.points[i].position;
            kept.onA[i] = a.orientation.conjugate() * (point - a.center);
            kept.onB[i] = b.orientation.conjugate() * (point - b.center);
            kept.feature[i] = contact.manifold.points[i].featureId;
            drifts[i] = Vec3::Zero();
        }
    }
    kept.count = c.pointCount;
    entry = kept;
    for (int i = 0; i < c.pointCount; ++i) {
        const ContactConstraintPoint& p = c.points[i];
        const Vec3 bend = 0.5 * h * h *
                          (b.angularVelocity.cross(b.angularVelocity.cross(p.rB)) -
                           a.angularVelocity.cross(a.angularVelocity.cross(p.rA)));
        drifts[i] += onPlane(bend, n);
    }
    entry.drift = reseatStale ? largest(drifts, c.pointCount) : 0;
}

// The patch slips as a whole when its friction reaches kSlipShare of its Coulomb limit (a point
// the normal block left unloaded is at its zero limit while the others stick).
bool AnchorTable::slips(const ContactConstraint& c) {
    Real friction = 0;  // N s
    Real limit = 0;
    for (int i = 0; i < c.pointCount; ++i) {
        const auto& t = c.points[i].tangentImpulse;
        friction += std::sqrt(t[0] * t[0] + t[1] * t[1]);  // hypot: 3 % of a pyramid step
        limit += c.friction * c.points[i].normalImpulse;
    }
    return c.friction == 0 || friction >= kSlipShare * limit;
}

void AnchorTable::release(std::uint32_t slot, bool slips) {
    if (slips && slot < entries_.size())
        entries_[slot].count = 0;
}

}  // namespace tumble
