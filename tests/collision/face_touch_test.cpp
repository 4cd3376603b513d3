// Convex shapes exactly touching, or 0.1 mm into, a face of a box: the contact must have the face's
// normal and the true depth. Exact touching is where GJK's closest points meet and their direction
// says nothing, so the contact comes from the penetration query started at zero depth; it once
// gave a cylinder lying on a long box the box's side normal with 5.5 m of depth (issue 20, item 1).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "clipping.h"
#include "tumble/collision/narrowphase.h"

namespace tumble {
namespace {

constexpr Real kPi = std::numbers::pi;
constexpr Real kDegree = kPi / 180;
constexpr Real kMargin = 0.02;
/// Issue 20's bounds: the normal within 1 degree of the face normal, the depth within 1e-6 m.
const Real kNormalCos = std::cos(1 * kDegree);
constexpr Real kDepthError = 1e-6;

Quat about(const Vec3& axis, Real angle) {
    return Quat(Eigen::AngleAxis<Real>(angle, axis.normalized()));
}

Real deepest(const Manifold& m) {
    Real s = m.points[0].separation;
    for (int i = 1; i < m.pointCount; ++i)
        s = std::min(s, m.points[static_cast<std::size_t>(i)].separation);
    return s;
}

TEST(FaceTouch, CylinderLyingOnALongBoxTouchingExactly) {
    // Issue 20, item 1: the manifold's normal was (0, 1, 0) with separation -5.5 m.
    const Shape box = Box{Vec3(30, 5, 0.5)};
    const Transform boxPose{Vec3(0, 0, -0.5), Quat::Identity()};
    const Shape cylinder = Cylinder{0.5, 0.5};
    const Transform cylinderPose{Vec3(22.028571428571421, 0, 0.5), about(Vec3::UnitX(), kPi / 2)};
    Manifold m;
    collide(box, boxPose, cylinder, cylinderPose, kMargin, m);
    ASSERT_GT(m.pointCount, 0);
    EXPECT_GT(m.normal.dot(Vec3::UnitZ()), kNormalCos) << m.normal.transpose();
    EXPECT_NEAR(deepest(m), 0, kDepthError);
}

/// One placed shape of the sweep, with its name for the failure message.
struct Candidate {
    std::string name;
    Shape shape;
    Quat base;  ///< orientation relative to the face frame (z = the face's outward normal)
    /// Known limit, NOT issue 20's 1e-6 m: a tilted cap's polygon has more than 4 points, and
    /// reduceContacts keeps the largest area among the sets holding a point within
    /// kDepthTolerance (1e-4 m) of the deepest, so the manifold may be that much shallower.
    /// Keeping the exact deepest point instead met 1e-6 m here but left CylinderStack's column
    /// rocking awake at 11-14 mm deep (the limit is 8 mm).
    Real depthError = kDepthError;
};

std::vector<Candidate> candidates() {
    const std::vector<Vec3> hullPoints = {Vec3(0.3, 0, -0.1),      Vec3(-0.2, 0.25, -0.15),
                                          Vec3(-0.15, -0.2, -0.2), Vec3(0.05, 0.05, 0.3),
                                          Vec3(0.1, -0.25, 0.1),   Vec3(-0.25, 0.1, 0.15),
                                          Vec3(0.2, 0.2, 0.05)};
    const Quat lying = about(Vec3::UnitX(), kPi / 2);
    return {
        {"cylinder lying", Cylinder{0.25, 0.3}, lying},
        {"cylinder standing", Cylinder{0.25, 0.3}, Quat::Identity(), detail::kDepthTolerance},
        {"capsule lying", Capsule{0.15, 0.3}, lying},
        {"capsule standing", Capsule{0.15, 0.3}, Quat::Identity()},
        {"hull", ConvexHull::fromPoints(hullPoints), about(Vec3(1, 2, 3), 0.7)},
        {"box", Box{Vec3(0.3, 0.2, 0.1)}, Quat::Identity()},
    };
}

/// A face of a posed box: outward normal, centre, two tangents and the half sizes along them.
struct Face {
    Vec3 normal, center, u, v;
    Real halfU, halfV;
};

Face faceOf(const Box& box, const Transform& pose, int k) {
    const int axis = k / 2, iu = (axis + 1) % 3, iv = (axis + 2) % 3;
    const Real sign = k % 2 == 0 ? 1 : -1;
    const Mat3 r = pose.rotation.toRotationMatrix();
    return {sign * r.col(axis),  pose.position + sign * box.halfExtents[axis] * r.col(axis),
            r.col(iu),           r.col(iv),
            box.halfExtents[iu], box.halfExtents[iv]};
}

/// Every candidate at random places on every face large enough to hold it, touching (depth 0)
/// and 0.1 mm in, each pair collided in both orders: the normal within 1 degree of the face's,
/// the deepest point's separation within 1e-6 m of -depth (except the known limit above).
TEST(FaceTouch, EveryConvexShapeOnTheFacesOfBoxes) {
    const std::vector<Box> boxes = {Box{Vec3(30, 5, 0.5)}, Box{Vec3(1, 1, 1)},
                                    Box{Vec3(3, 2, 0.25)}, Box{Vec3(0.7, 0.9, 0.6)}};
    std::mt19937_64 rng(20);
    std::uniform_real_distribution<Real> unit(-1, 1);
    int trials = 0, failures = 0;
    for (const Candidate& candidate : candidates()) {
        const Real reach = boundingRadius(candidate.shape);
        const int failuresBefore = failures;
        Real worstDepth = 0, worstCos = 1;
        std::uniform_int_distribution<std::size_t> pickBox(0, boxes.size() - 1);
        std::uniform_int_distribution<int> pickFace(0, 5), pickCase(0, 3);
        int placed = 0;
        while (placed < 1000) {
            const Box& box = boxes[pickBox(rng)];
            // Half the boxes axis-aligned (as the issue's), half turned at random.
            const Quat boxTurn =
                pickCase(rng) < 2 ? Quat::Identity()
                                  : Quat(unit(rng), unit(rng), unit(rng), unit(rng)).normalized();
            const Transform boxPose{Vec3(unit(rng), unit(rng), unit(rng)), boxTurn};
            const Face face = faceOf(box, boxPose, pickFace(rng));
            if (face.halfU < reach + 0.01 || face.halfV < reach + 0.01)
                continue;  // too small a face for the shape
            // The face frame (x = u, y = v, z = normal); a spin about the normal, and a tilt of
            // up to 2 degrees in three cases out of four (none in the fourth: faces parallel).
            const Quat frame((Mat3() << face.u, face.v, face.normal).finished().determinant() > 0
                                 ? Quat((Mat3() << face.u, face.v, face.normal).finished())
                                 : Quat((Mat3() << face.v, face.u, face.normal).finished()));
            const Real tilt = pickCase(rng) == 0 ? 0 : 2 * kDegree * std::abs(unit(rng));
            const Quat turn = about(Vec3(unit(rng), unit(rng), 0) + 1e-9 * Vec3::UnitX(), tilt) *
                              about(Vec3::UnitZ(), kPi * unit(rng));
            const Quat rotation = (frame * turn * candidate.base).normalized();
            const Vec3 lateral = (face.halfU - reach) * unit(rng) * face.u +
                                 (face.halfV - reach) * unit(rng) * face.v;
            for (const Real depth : {0.0, 1e-4}) {
                // The shape's lowest point along -normal sits `depth` below the face plane.
                const Vec3 low =
                    rotation * support(candidate.shape, rotation.conjugate() * Vec3(-face.normal));
                const Vec3 position = face.center + lateral - face.normal.dot(low) * face.normal -
                                      depth * face.normal;
                const Transform shapePose{position, rotation};
                for (const bool boxFirst : {true, false}) {
                    Manifold m;
                    if (boxFirst)
                        collide(box, boxPose, candidate.shape, shapePose, kMargin, m);
                    else
                        collide(candidate.shape, shapePose, box, boxPose, kMargin, m);
                    const Vec3 expected = boxFirst ? face.normal : Vec3(-face.normal);
                    ++trials;
                    const Real depthError =
                        m.pointCount > 0 ? std::abs(deepest(m) + depth) : depth + kMargin;
                    worstDepth = std::max(worstDepth, depthError);
                    worstCos = std::min(worstCos, m.normal.dot(expected));
                    const bool ok = m.pointCount > 0 && m.normal.dot(expected) >= kNormalCos &&
                                    depthError <= candidate.depthError;
                    if (!ok && ++failures <= 10) {
                        ADD_FAILURE()
                            << candidate.name << " (" << (boxFirst ? "box first" : "box second")
                            << "), depth " << depth << ", tilt " << tilt / kDegree << " deg, box "
                            << box.halfExtents.transpose() << ": " << m.pointCount
                            << " points, normal " << m.normal.transpose() << " (expected "
                            << expected.transpose() << "), deepest "
                            << (m.pointCount > 0 ? deepest(m) : 0);
                    }
                }
            }
            ++placed;
        }
        std::printf("face touch: %s: %d wrong of %d, worst depth error %.3g m, normal %.3g deg\n",
                    candidate.name.c_str(), failures - failuresBefore, 4 * placed, worstDepth,
                    std::acos(std::min<Real>(1, worstCos)) / kDegree);
    }
    std::printf("face touch: %d contacts, %d wrong\n", trials, failures);
    EXPECT_EQ(failures, 0);
}

}  // namespace
}  // namespace tumble
