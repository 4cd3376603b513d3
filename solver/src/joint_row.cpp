#include "tumble/solver/joint_row.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "tumble/solver/contact_solver.h"

namespace tumble {
namespace {

using Mat6 = Eigen::Matrix<Real, 6, 6>;
using Vec6 = Eigen::Matrix<Real, 6, 1>;

// Geometric stiffness: the (omega h)^2 left to the explicit part when beta > 0 is
// 2 kExplicitShare. 1/2 (a = 1, half the single-mode limit of 2): with 1 (a^2 = 2) the chain
// still blew up -- neighbouring links couple, and Lambda lags a step.
constexpr Real kExplicitShare = 0.5;
// phi = kTensionDamping x the relative change of S since the last step (1 at most). Measured
// (h = 1/60): 5 let 2 rods under a 100x load gain 0.05 J in 300 s, 10 and 20 never gained;
// a 30-bead chain kept 99.9, 99.7, 96.9 % of its swing after 20 s at 10, 20, 200.
constexpr Real kTensionDamping = 20;

// Anchors closer than this give the distance row no direction (m).
constexpr Real kMinimumLength = 1e-12;

bool hasPointBlock(JointType type) {
    return type == JointType::Ball || type == JointType::Hinge || type == JointType::Fixed;
}
bool hasAxialRow(JointType type) {
    return type == JointType::Hinge || type == JointType::Slider || type == JointType::Distance;
}

// What the exact rotation of one step (integratePositions: q <- exp(h w / 2) q) does to a lever
// arm r beyond its linearisation h w x r: the chord's second-order drift (m).
Vec3 rotationDrift(const Vec3& w, const Vec3& r, Real h) {
    const Real angle = h * w.norm();
    if (angle == 0)
        return Vec3::Zero();
    const Vec3 rotated = Eigen::AngleAxis<Real>(angle, w / w.norm()) * r;
    return rotated - r - h * w.cross(r);
}

Vec3 anchorVelocity(const SolverBody& body, const Vec3& r) {
    return body.linearVelocity + body.angularVelocity.cross(r);
}

// The impulse P on B at rB, -P on A at its lever arm.
void applyLinear(SolverBody& a, SolverBody& b, const JointRow& row, const Vec3& impulse) {
    applyImpulse(a, -impulse, row.leverA);
    applyImpulse(b, impulse, row.rB);
}

void applyAngular(SolverBody& a, SolverBody& b, const Vec3& impulse) {
    a.angularVelocity -= a.inverseInertia * impulse;
    b.angularVelocity += b.inverseInertia * impulse;
}

void applyAxial(SolverBody& a, SolverBody& b, const JointRow& row, Real lambda) {
    a.linearVelocity -= (a.inverseMass * lambda) * row.axialLinear;
    a.angularVelocity -= lambda * (a.inverseInertia * row.axialAngularA);
    b.linearVelocity += (b.inverseMass * lambda) * row.axialLinear;
    b.angularVelocity += lambda * (b.inverseInertia * row.axialAngularB);
}

Real axialSpeed(const SolverBody& a, const SolverBody& b, const JointRow& row) {
    return row.axialLinear.dot(b.linearVelocity - a.linearVelocity) +
           row.axialAngularB.dot(b.angularVelocity) - row.axialAngularA.dot(a.angularVelocity);
}

// The equality rows of the joint's type, their errors and the inverse of their block.
void prepareEquality(const SolverBody& a, const SolverBody& b, JointRow& row) {
    const std::array<Vec3, 2> normal = frictionBasis(row.axis);
    const std::array<Vec3, 3> world{Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
    int n = 0;
    const auto add = [&](const Vec3& direction) { row.directions[n++] = direction; };
    if (hasPointBlock(row.type)) {
        for (const Vec3& d : world)
            add(d);
    } else if (row.type == JointType::Slider) {
        add(normal[0]);
        add(normal[1]);
    }
    row.linearRows = n;
    if (row.type == JointType::Hinge) {
        add(normal[0]);
        add(normal[1]);
    } else if (row.type == JointType::Fixed || row.type == JointType::Slider) {
        for (const Vec3& d : world)
            add(d);
    }
    row.angularRows = n - row.linearRows;
    row.error.setZero();
    for (int k = 0; k < n; ++k) {
        row.error(k) =
            row.directions[k].dot(k < row.linearRows ? row.separation : row.angularError);
    }
    // K(i, j): row i's velocity change per unit impulse of row j.
    Mat6 k = Mat6::Identity();  // identity beyond n keeps the fixed-size inverse regular
    for (int j = 0; j < n; ++j) {
        const Vec3& d = row.directions[j];
        const bool linearJ = j < row.linearRows;
        const Vec3 spinA = a.inverseInertia * (linearJ ? Vec3(row.leverA.cross(d)) : d);
        const Vec3 spinB = b.inverseInertia * (linearJ ? Vec3(row.rB.cross(d)) : d);
        const Vec3 velocity = linearJ ? Vec3((a.inverseMass + b.inverseMass) * d +
                                             spinB.cross(row.rB) + spinA.cross(row.leverA))
                                      : Vec3(spinB.cross(row.rB) + spinA.cross(row.leverA));
        for (int i = 0; i < n; ++i) {
            k(i, j) = row.directions[i].dot(i < row.linearRows ? velocity : Vec3(spinB + spinA));
        }
    }
    const Eigen::LDLT<Mat6> factor(k);
    if (factor.info() != Eigen::Success || !factor.isPositive()) {
        row.linearRows = row.angularRows = 0;
        row.blockInverse.setZero();
        return;
    }
    row.blockInverse = factor.solve(Mat6::Identity());
    row.blockInverse.bottomRows(6 - n).setZero();
    row.blockInverse.rightCols(6 - n).setZero();
}

// The axial row's Jacobian, effective mass and coordinate for the row's type.
void prepareAxial(const SolverBody& a, const SolverBody& b, JointRow& row) {
    row.axialLinear.setZero();
    row.axialAngularA.setZero();
    row.axialAngularB.setZero();
    switch (row.type) {
        case JointType::Hinge:
            row.axialAngularA = row.axis;
            row.axialAngularB = row.axis;
            break;
        case JointType::Slider:
            row.axialLinear = row.axis;
            row.axialAngularA = row.leverA.cross(row.axis);
            row.axialAngularB = row.rB.cross(row.axis);
            break;
        case JointType::Distance: {
            const Vec3 n =
                row.position > kMinimumLength ? Vec3(row.separation / row.position) : row.axis;
            row.axialLinear = n;
            row.axialAngularA = row.rA.cross(n);
            row.axialAngularB = row.rB.cross(n);
            break;
        }
        default:
            row.axialMass = 0;
            return;
    }
    const Real inverse = (a.inverseMass + b.inverseMass) * row.axialLinear.squaredNorm() +
                         row.axialAngularA.dot(a.inverseInertia * row.axialAngularA) +
                         row.axialAngularB.dot(b.inverseInertia * row.axialAngularB);
    row.axialMass = inverse > 0 ? 1 / inverse : 0;
}

// Target of a one-sided limit row from its slack s (>= 0 satisfied), as for a contact: a gap may
// close within the step but not beyond; a violation is pushed out at the bias rate.
Real limitTarget(Real slack, Real bias, Real inverseH) {
    return slack > 0 ? -slack * inverseH : -bias * slack * inverseH;
}

Real solveAxial(SolverBody& a, SolverBody& b, JointRow& row, Real omega, Real bias, Real inverseH,
                Real h) {
    Real largest = 0;
    const auto update = [&](Real& impulse, Real target, Real low, Real high) {
        const Real gap = axialSpeed(a, b, row) - target;
        const Real next = std::clamp(impulse - omega * row.axialMass * gap, low, high);
        applyAxial(a, b, row, next - impulse);
        largest = std::max(largest, std::abs(next - impulse) / row.axialMass);
        impulse = next;
    };
    constexpr Real kInfinity = std::numeric_limits<Real>::infinity();
    if (row.motor) {
        const Real cap = row.maxMotorForce * h;
        update(row.motorImpulse, row.motorSpeed, -cap, cap);
    }
    if (row.lower == row.upper) {
        update(row.lowerImpulse, -(bias * (row.position - row.lower) + row.axialDrift) * inverseH,
               -kInfinity, kInfinity);
        return largest;
    }
    // The slack each limit will have at the end of the step, drift included.
    if (std::isfinite(row.lower)) {
        update(row.lowerImpulse,
               limitTarget(row.position - row.lower + row.axialDrift, bias, inverseH), 0,
               kInfinity);
    }
    if (std::isfinite(row.upper)) {
        update(row.upperImpulse,
               -limitTarget(row.upper - row.position - row.axialDrift, bias, inverseH), -kInfinity,
               0);
    }
    return largest;
}

// The curvature drift from the current velocities: the closest guess of the velocities the
// bodies will move with. Evaluated again in every sweep, because a body of small inertia on a
// long lever turns much faster or slower by the end of the solve than after the warm start.
void updateDrift(const SolverBody& a, const SolverBody& b, JointRow& row, Real h) {
    const Vec3 drift =
        rotationDrift(b.angularVelocity, row.rB, h) - rotationDrift(a.angularVelocity, row.rA, h);
    row.pointDrift = row.type == JointType::Slider
                         ? rotationDrift(b.angularVelocity, row.rB, h) -
                               rotationDrift(a.angularVelocity, row.leverA, h)
                         : drift;
    if (row.type == JointType::Distance && row.axialMass > 0) {
        const Vec3 relative = anchorVelocity(b, row.rB) - anchorVelocity(a, row.rA);
        const Vec3 next = row.separation + h * relative + drift;
        row.axialDrift = next.norm() - row.position - h * row.axialLinear.dot(relative);
    }
}

// One body of applyJointGeometricStiffness: s = h S from last step's Lambda, previous = from
// the step's before.
void stiffen(SolverBody& body, const Mat3& s, const Mat3& previous) {
    // K = -(symmetric negative part of h S) >= 0 (kg m^2).
    const Eigen::SelfAdjointEigenSolver<Mat3> parts(0.5 * (s + s.transpose()));
    const Vec3 restoring = (-parts.eigenvalues()).cwiseMax(0);
    if (restoring.isZero())
        return;
    const Mat3 k = parts.eigenvectors() * restoring.asDiagonal() * parts.eigenvectors().transpose();
    // B = (I^-1)^(1/2); G = B K B, whose largest eigenvalue is a^2 = (omega h)^2.
    const Eigen::SelfAdjointEigenSolver<Mat3> inertia(body.inverseInertia);
    const Mat3 root = inertia.eigenvectors() *
                      inertia.eigenvalues().cwiseMax(0).cwiseSqrt().asDiagonal() *
                      inertia.eigenvectors().transpose();
    const Eigen::SelfAdjointEigenSolver<Mat3> modes(root * k * root);
    const Real a2 = modes.eigenvalues().maxCoeff();
    if (!(a2 > 2 * kExplicitShare))
        return;  // resolved: symplectic Euler keeps it, untouched
    const Real beta = 0.5 - kExplicitShare / a2;
    // A^-1 = B (1 + beta G)^-1 B. Steady tension keeps w0 (symplectic Euler on A); a changing
    // one starts towards A^-1 I w0 = w0 - beta A^-1 K w0 (backward Euler's share).
    const Vec3 scaled = (1 + beta * modes.eigenvalues().array()).inverse().matrix();
    const Mat3 inverse =
        root * modes.eigenvectors() * scaled.asDiagonal() * modes.eigenvectors().transpose() * root;
    const Real phi = std::min<Real>(1, kTensionDamping * (s - previous).norm() / s.norm());
    body.angularVelocity -= phi * beta * (inverse * (k * body.angularVelocity));
    body.inverseInertia = 0.5 * (inverse + inverse.transpose());
}

}  // namespace

void prepareJointRows(std::span<SolverBody> bodies, std::span<JointRow> rows, Real h,
                      bool warmStart) {
    for (JointRow& row : rows) {
        SolverBody& a = bodies[row.bodyA];
        SolverBody& b = bodies[row.bodyB];
        row.active = a.inverseMass > 0 || b.inverseMass > 0;
        if (!warmStart || !row.active) {
            row.linearImpulse.setZero();
            row.angularImpulse.setZero();
            row.motorImpulse = row.lowerImpulse = row.upperImpulse = 0;
        }
        if (!row.active)
            continue;
        row.leverA = row.type == JointType::Slider ? Vec3(row.rA + row.separation) : row.rA;
        prepareEquality(a, b, row);
        prepareAxial(a, b, row);
        if (!hasAxialRow(row.type) || row.axialMass == 0) {
            row.motorImpulse = row.lowerImpulse = row.upperImpulse = 0;
        }
        const Real cap = row.motor ? row.maxMotorForce * h : 0;
        row.motorImpulse = std::clamp(row.motorImpulse, -cap, cap);
        if (row.lower != row.upper) {
            if (!std::isfinite(row.lower))
                row.lowerImpulse = 0;
            if (!std::isfinite(row.upper))
                row.upperImpulse = 0;
            row.lowerImpulse = std::max<Real>(row.lowerImpulse, 0);
            row.upperImpulse = std::min<Real>(row.upperImpulse, 0);
        } else {
            row.upperImpulse = 0;
        }
        // Only the parts along this step's rows: the axes may have turned since the last step.
        const Vec3 linear = row.linearImpulse;
        const Vec3 angular = row.angularImpulse;
        row.linearImpulse.setZero();
        row.angularImpulse.setZero();
        for (int k = 0; k < row.linearRows; ++k)
            row.linearImpulse += row.directions[k].dot(linear) * row.directions[k];
        for (int k = row.linearRows; k < row.linearRows + row.angularRows; ++k)
            row.angularImpulse += row.directions[k].dot(angular) * row.directions[k];
        applyLinear(a, b, row, row.linearImpulse);
        applyAngular(a, b, row.angularImpulse);
        applyAxial(a, b, row, row.motorImpulse + row.lowerImpulse + row.upperImpulse);
    }
    for (JointRow& row : rows) {
        if (row.active)
            updateDrift(bodies[row.bodyA], bodies[row.bodyB], row, h);
    }
}

Real solveJointRows(std::span<SolverBody> bodies, std::span<JointRow> rows, Real relaxation,
                    Real bias, Real inverseH) {
    const Real h = 1 / inverseH;
    Real largest = 0;
    for (JointRow& row : rows) {
        if (!row.active)
            continue;
        SolverBody& a = bodies[row.bodyA];
        SolverBody& b = bodies[row.bodyB];
        updateDrift(a, b, row, h);
        if (row.axialMass > 0)
            largest = std::max(largest, solveAxial(a, b, row, relaxation, bias, inverseH, h));

        const int n = row.linearRows + row.angularRows;
        if (n == 0 || row.blockSolved)
            continue;
        const Vec3 relative = anchorVelocity(b, row.rB) - anchorVelocity(a, row.leverA);
        const Vec3 spin = b.angularVelocity - a.angularVelocity;
        Vec6 gap = Vec6::Zero();
        for (int k = 0; k < row.linearRows; ++k) {
            const Vec3& d = row.directions[k];
            gap(k) = d.dot(relative) + inverseH * (bias * row.error(k) + d.dot(row.pointDrift));
        }
        for (int k = row.linearRows; k < n; ++k)
            gap(k) = row.directions[k].dot(spin) + inverseH * bias * row.error(k);
        const Vec6 delta = -relaxation * (row.blockInverse * gap);
        Vec3 linear = Vec3::Zero();
        Vec3 angular = Vec3::Zero();
        for (int k = 0; k < row.linearRows; ++k)
            linear += delta(k) * row.directions[k];
        for (int k = row.linearRows; k < n; ++k)
            angular += delta(k) * row.directions[k];
        applyLinear(a, b, row, linear);
        applyAngular(a, b, angular);
        row.linearImpulse += linear;
        row.angularImpulse += angular;
        largest = std::max(largest, relaxation * gap.norm());
    }
    return largest;
}

void solveJointPositions(std::span<SolverBody> pseudoBodies, std::span<JointRow> rows, Real bias,
                         Real inverseH, int sweeps) {
    constexpr Real kInfinity = std::numeric_limits<Real>::infinity();
    for (JointRow& row : rows) {
        row.pseudoLower = 0;
        row.pseudoUpper = 0;
    }
    for (int sweep = 0; sweep < sweeps; ++sweep) {
        for (JointRow& row : rows) {
            if (!row.active)
                continue;
            SolverBody& a = pseudoBodies[row.bodyA];
            SolverBody& b = pseudoBodies[row.bodyB];
            if (row.axialMass > 0) {
                const auto update = [&](Real& impulse, Real target, Real low, Real high) {
                    const Real gap = axialSpeed(a, b, row) - target;
                    const Real next = std::clamp(impulse - row.axialMass * gap, low, high);
                    applyAxial(a, b, row, next - impulse);
                    impulse = next;
                };
                if (row.lower == row.upper) {
                    update(row.pseudoLower, -bias * (row.position - row.lower) * inverseH,
                           -kInfinity, kInfinity);
                } else {
                    // Only a violated limit is pushed out; one not reached asks for nothing.
                    if (std::isfinite(row.lower)) {
                        update(row.pseudoLower,
                               -bias * std::min<Real>(row.position - row.lower, 0) * inverseH, 0,
                               kInfinity);
                    }
                    if (std::isfinite(row.upper)) {
                        update(row.pseudoUpper,
                               bias * std::min<Real>(row.upper - row.position, 0) * inverseH,
                               -kInfinity, 0);
                    }
                }
            }
            const int n = row.linearRows + row.angularRows;
            if (n == 0)
                continue;
            const Vec3 relative = anchorVelocity(b, row.rB) - anchorVelocity(a, row.leverA);
            const Vec3 spin = b.angularVelocity - a.angularVelocity;
            Vec6 gap = Vec6::Zero();
            for (int k = 0; k < n; ++k) {
                gap(k) = row.directions[k].dot(k < row.linearRows ? relative : spin) +
                         inverseH * bias * row.error(k);
            }
            const Vec6 delta = -(row.blockInverse * gap);
            Vec3 linear = Vec3::Zero();
            Vec3 angular = Vec3::Zero();
            for (int k = 0; k < row.linearRows; ++k)
                linear += delta(k) * row.directions[k];
            for (int k = row.linearRows; k < n; ++k)
                angular += delta(k) * row.directions[k];
            applyLinear(a, b, row, linear);
            applyAngular(a, b, angular);
        }
    }
}

void buildJointBlockRows(std::span<const SolverBody> bodies, std::span<JointRow> rows,
                         std::vector<SpringRow>& block) {
    block.clear();
    for (JointRow& row : rows) {
        row.blockSolved = row.active && row.type == JointType::Ball && row.linearRows == 3 &&
                          row.bodyA != row.bodyB;
        if (!row.blockSolved)
            continue;
        const SolverBody& a = bodies[row.bodyA];
        const SolverBody& b = bodies[row.bodyB];
        for (int k = 0; k < 3; ++k) {
            SpringRow r;
            r.bodyA = row.bodyA;
            r.bodyB = row.bodyB;
            r.rA = row.leverA;
            r.rB = row.rB;
            r.direction = row.directions[k];
            r.angularA = row.leverA.cross(r.direction);
            r.angularB = row.rB.cross(r.direction);
            r.angularImpulseA = a.inverseInertia * r.angularA;
            r.angularImpulseB = b.inverseInertia * r.angularB;
            const Real inverse = a.inverseMass + b.inverseMass + r.angularA.dot(r.angularImpulseA) +
                                 r.angularB.dot(r.angularImpulseB);
            r.mass = inverse > 0 ? 1 / inverse : 0;
            r.softness = 0;
            r.impulse = r.direction.dot(row.linearImpulse);
            block.push_back(r);
        }
    }
}

void updateJointBlockTargets(std::span<const SolverBody> bodies, std::span<JointRow> rows,
                             std::span<SpringRow> block, Real bias, Real inverseH) {
    std::size_t next = 0;
    for (JointRow& row : rows) {
        if (!row.blockSolved)
            continue;
        updateDrift(bodies[row.bodyA], bodies[row.bodyB], row, 1 / inverseH);
        for (int k = 0; k < 3; ++k, ++next) {
            block[next].bias =
                inverseH * (bias * row.error(k) + row.directions[k].dot(row.pointDrift));
        }
    }
}

void storeJointBlockImpulses(std::span<JointRow> rows, std::span<const SpringRow> block) {
    std::size_t next = 0;
    for (JointRow& row : rows) {
        if (!row.blockSolved)
            continue;
        row.linearImpulse.setZero();
        for (int k = 0; k < 3; ++k, ++next)
            row.linearImpulse += block[next].impulse * block[next].direction;
    }
}

void applyJointGeometricStiffness(std::span<SolverBody> bodies, std::span<const JointRow> rows,
                                  Real h, std::vector<Mat3>& stiffness) {
    // stiffness[i]: h S of body i from last step's Lambda; stiffness[n + i]: from the one before.
    const std::size_t n = bodies.size();
    stiffness.assign(2 * n, Mat3::Zero());
    bool any = false;
    // dtau / dtheta of an impulse p at lever r, times h: (r p' - (p . r) 1) h.
    const auto add = [&](std::uint32_t body, const Vec3& r, const Vec3& p, const Vec3& previous) {
        if (bodies[body].inverseInertia.isZero())
            return;
        stiffness[body] += h * (r * p.transpose() - p.dot(r) * Mat3::Identity());
        stiffness[n + body] += h * (r * previous.transpose() - previous.dot(r) * Mat3::Identity());
        any = true;
    };
    for (const JointRow& row : rows) {
        if (!(hasPointBlock(row.type) || row.type == JointType::Slider) ||
            row.linearImpulse.isZero())
            continue;
        const Vec3 leverA = row.type == JointType::Slider ? Vec3(row.rA + row.separation) : row.rA;
        add(row.bodyA, leverA, -row.linearImpulse, -row.previousLinearImpulse);
        add(row.bodyB, row.rB, row.linearImpulse, row.previousLinearImpulse);
    }
    if (!any)
        return;
    for (std::size_t i = 0; i < n; ++i) {
        if (!stiffness[i].isZero())
            stiffen(bodies[i], stiffness[i], stiffness[n + i]);
    }
}

Vec3 jointReactionForce(const JointRow& row, Real h) {
    const Real axial = row.motorImpulse + row.lowerImpulse + row.upperImpulse;
    return (row.linearImpulse + axial * row.axialLinear) / h;
}

Vec3 jointReactionTorque(const JointRow& row, Real h) {
    const Real axial = row.motorImpulse + row.lowerImpulse + row.upperImpulse;
    const Vec3 pure = row.type == JointType::Hinge ? Vec3(axial * row.axis) : Vec3::Zero();
    return (row.angularImpulse + pure) / h;
}

}  // namespace tumble
