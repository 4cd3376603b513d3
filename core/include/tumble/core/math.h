#pragma once
/// The numeric vocabulary of Tumble. Every length is in metres, every time in seconds, every mass
/// in kilograms, every angle in radians. Frames are right-handed.
///
/// Quaternions are Eigen's: the constructor order is Quat(w, x, y, z) -- scalar first -- while
/// Quat::coeffs() stores (x, y, z, w). Never bind an Eigen expression to `auto`: it would keep a
/// reference to temporaries.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tumble {

/// The one scalar type of the engine. `double` for engineering accuracy and large coordinates.
using Real = double;
using Vec3 = Eigen::Matrix<Real, 3, 1>;
using Mat3 = Eigen::Matrix<Real, 3, 3>;
using Quat = Eigen::Quaternion<Real>;

/// A rigid transform: x_world = rotation * x_local + position.
struct Transform {
    Vec3 position = Vec3::Zero();      ///< origin of the local frame, in the parent frame (m)
    Quat rotation = Quat::Identity();  ///< unit quaternion, local to parent

    Vec3 apply(const Vec3& local) const { return rotation * local + position; }
    Vec3 applyInverse(const Vec3& world) const { return rotation.conjugate() * (world - position); }
};

/// The skew-symmetric matrix with skew(a) * b == a.cross(b).
inline Mat3 skew(const Vec3& a) {
    Mat3 m;
    m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
    return m;
}

inline bool isFinite(const Vec3& v) {
    return v.allFinite();
}
inline bool isFinite(const Quat& q) {
    return q.coeffs().allFinite();
}
inline bool isFinite(const Mat3& m) {
    return m.allFinite();
}

}  // namespace tumble
