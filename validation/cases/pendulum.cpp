// pendulum: pendulums released from rest at 10, 90 and 170 deg, h = 1/240, against the exact
// period T = 4 sqrt(Leq / g) K(sin(theta0 / 2)), K the complete elliptic integral of the first
// kind (computed by the arithmetic-geometric mean, K(k) = pi / (2 AGM(1, sqrt(1 - k^2)))).
//
// Two pendulums per angle:
// - rod: a distance joint (rod, L = 1 m) from a world point to the centre of mass of a 1 kg
//   sphere: no torque reaches the sphere, so it is exactly a simple pendulum, Leq = L. The rod
//   length is measured every step; it must stay within 1e-4 of L (relative).
// - hinge: a 1 kg sphere of radius 0.1 m on a hinge 1 m above its centre: a physical pendulum,
//   Leq = (I_c + m L^2) / (m L) with I_c = 2/5 m r^2; the hinge's anchor drift is measured the
//   same way (distance from the pivot to the sphere's anchor point).
//
// The period is twice the mean spacing of the crossings of the vertical (x = 0, linear
// interpolation between steps) over the run.

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "../case.h"
#include "tumble/tumble.h"

namespace tumble::validation {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kGravity = 9.81;
constexpr double kLength = 1;
constexpr double kMass = 1;
constexpr double kRadius = 0.1;
constexpr double kStep = 1.0 / 240.0;

double ellipticK(double k) {
    double a = 1;
    double b = std::sqrt(1 - k * k);
    for (int i = 0; i < 30 && std::abs(a - b) > 1e-15 * a; ++i) {
        const double next = 0.5 * (a + b);
        b = std::sqrt(a * b);
        a = next;
    }
    return kPi / (2 * a);
}

struct Swing {
    double period = 0;       // measured (s)
    double exact = 0;        // (s)
    double lengthError = 0;  // max |anchor distance - L| / L
    bool finite = true;
};

Swing swing(double theta0Degrees, bool hinge, double periods) {
    const double theta0 = theta0Degrees * kPi / 180;
    WorldDef settings;
    settings.gravity = Vec3(0, 0, -kGravity);
    settings.timeStep = kStep;
    settings.enableSleep = false;
    World world(settings);
    BodyDef def;
    def.position = Vec3(kLength * std::sin(theta0), 0, -kLength * std::cos(theta0));
    MassProperties mass;
    mass.mass = kMass;
    const double inertia = 0.4 * kMass * kRadius * kRadius;
    mass.inertia = Mat3::Identity() * inertia;
    def.mass = mass;
    const BodyId bob = world.createBody(def);
    JointDef joint;
    joint.bodyA = bob;
    if (hinge) {
        joint.type = JointType::Hinge;
        joint.anchor = Vec3::Zero();
        joint.axis = Vec3::UnitY();
    } else {
        joint.type = JointType::Distance;
        joint.anchor = def.position;   // A's end: the centre of mass
        joint.anchorB = Vec3::Zero();  // the world pivot
    }
    world.createJoint(joint);
    const Vec3 localPivot = -def.position;  // the hinge anchor in the bob's frame (no rotation)

    Swing s;
    const double lengthEq =
        hinge ? (inertia + kMass * kLength * kLength) / (kMass * kLength) : kLength;
    s.exact = 4 * std::sqrt(lengthEq / kGravity) * ellipticK(std::sin(theta0 / 2));
    const int steps = static_cast<int>(periods * s.exact / kStep) + 2;
    std::vector<double> crossings;
    double previousX = world.position(bob).x();
    for (int i = 1; i <= steps; ++i) {
        if (!world.step().ok()) {
            s.finite = false;
            return s;
        }
        const Vec3 x = world.position(bob);
        // Rod: its length; hinge: how far the bob's anchor point has left the pivot.
        const double error = hinge ? (x + world.orientation(bob) * localPivot).norm() / kLength
                                   : std::abs(x.norm() - kLength) / kLength;
        s.lengthError = std::max(s.lengthError, error);
        if ((previousX > 0) != (x.x() > 0)) {
            const double fraction = previousX / (previousX - x.x());
            crossings.push_back((i - 1 + fraction) * kStep);
        }
        previousX = x.x();
    }
    if (crossings.size() >= 2) {
        s.period =
            2 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    }
    return s;
}

CaseResult run(const CaseOptions& options) {
    CaseResult r;
    const double periodTolerance = 0.005;
    const double lengthTolerance = 1e-4;
    r.tolerance("period relative error", periodTolerance);
    r.tolerance("rod length / anchor drift relative", lengthTolerance);
    const double periods = options.fast ? 2 : 6;
    for (const double angle : {10.0, 90.0, 170.0}) {
        for (const bool hinge : {false, true}) {
            const Swing s = swing(angle, hinge, periods);
            const double error = s.period / s.exact - 1;
            r.table.push_back({{{"theta0 (deg)", angle},
                                {"hinge", hinge ? 1.0 : 0.0},
                                {"exact T (s)", s.exact},
                                {"measured T (s)", s.period},
                                {"T rel. error", error},
                                {"length error", s.lengthError}}});
            const std::string what =
                std::string(hinge ? "hinge" : "rod") + " at " + std::to_string(angle) + " deg";
            r.check(s.finite, what + ": state went non-finite");
            r.check(std::abs(error) <= periodTolerance,
                    what + ": period error " + std::to_string(error) + " beyond 0.5 %");
            r.check(s.lengthError <= lengthTolerance,
                    what + ": length error " + std::to_string(s.lengthError) + " beyond 1e-4");
        }
    }
    return r;
}

}  // namespace

ValidationCase pendulumCase() {
    return {"pendulum",
            "rod and hinge pendulums from 10, 90, 170 deg: period within 0.5 % of the elliptic "
            "integral, length within 1e-4 (h = 1/240)",
            run};
}

}  // namespace tumble::validation
