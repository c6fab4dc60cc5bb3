// Basic geometric types and conventions shared by every vb module.
//
// Frames: world W is x east, y north, z up, origin at the centre of the map (as the original
// Verti-Bench). Vehicle frame B is ISO 8855: x forward, y left, z up. SI units, radians.
#pragma once

#include <algorithm>
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vb {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;
using Mat3 = Eigen::Matrix3d;

// Rigid transform: p_W = position + rotation * p_B.
struct Pose {
  Vec3 position = Vec3::Zero();
  Quat rotation = Quat::Identity();
};

// Roll, pitch, yaw (rad) of a rotation, intrinsic z-y'-x'' (yaw first), as Chrono's Cardan XYZ
// read-out used by the original for its roll/pitch metrics.
struct Rpy {
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double yaw_rad = 0.0;
};

inline Rpy ToRpy(const Quat& q) {
  const Mat3 r = q.toRotationMatrix();
  Rpy out;
  out.pitch_rad = std::asin(std::max(-1.0, std::min(1.0, -r(2, 0))));
  out.roll_rad = std::atan2(r(2, 1), r(2, 2));
  out.yaw_rad = std::atan2(r(1, 0), r(0, 0));
  return out;
}

inline Quat FromYaw(double yaw_rad) { return Quat(Eigen::AngleAxisd(yaw_rad, Vec3::UnitZ())); }

// Wraps an angle to [-pi, pi).
inline double WrapAngle(double a) {
  constexpr double kPi = 3.14159265358979323846;
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a < 0) a += 2.0 * kPi;
  return a - kPi;
}

constexpr double kPi = 3.14159265358979323846;
constexpr double kGravity = 9.81;  // m/s^2, as the original (Chrono demos use 9.81)

}  // namespace vb
