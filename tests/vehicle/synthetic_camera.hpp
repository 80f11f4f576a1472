#pragma once
// Synthetic cameras for the vehicle tests: known K, height and attitude, ground points
// projected exactly, so that eq. (1) and the calibration can be checked against truth.
#include <Eigen/Geometry>

#include "mapfuse/vehicle/camera.hpp"

namespace mapfuse::test {

inline Eigen::Matrix3d syntheticK() {
  Eigen::Matrix3d K;
  K << 720.0, 0.0, 640.0, 0.0, 720.0, 360.0, 0.0, 0.0, 1.0;
  return K;
}

/// Camera-frame rotation of a camera pitched by `pitch` and rolled by `roll` relative to the
/// level camera (tiltNormal convention).
inline Eigen::Matrix3d tiltRotation(double pitch, double roll) {
  return (Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

/// A ground point `forward` m ahead and `left` m to the left, in the tilted camera frame.
inline Eigen::Vector3d groundPointCam(double forward, double left, double height, double pitch,
                                      double roll) {
  return tiltRotation(pitch, roll) * Eigen::Vector3d(-left, height, forward);
}

}  // namespace mapfuse::test
