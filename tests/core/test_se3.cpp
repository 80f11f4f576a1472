#include <catch2/catch.hpp>

#include <random>

#include "mapfuse/core/se3.hpp"

using namespace mapfuse;

namespace {
constexpr double kTol = 1e-9;  // numerical round-off tolerance for closed-form identities
}

TEST_CASE("poseFromXyzRpy follows R = Rz(yaw) Ry(pitch) Rx(roll)", "[core][se3]") {
  const Pose3 T = poseFromXyzRpy(1, 2, 3, 0.1, -0.2, 0.3);
  const Eigen::Matrix3d expected = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()))
                                       .toRotationMatrix();
  CHECK((T.linear() - expected).norm() < kTol);
  CHECK((T.translation() - Eigen::Vector3d(1, 2, 3)).norm() < kTol);
  const Eigen::Vector3d rpy = rpyFromRotation(T.linear());
  CHECK(rpy.x() == Approx(0.1).margin(kTol));
  CHECK(rpy.y() == Approx(-0.2).margin(kTol));
  CHECK(rpy.z() == Approx(0.3).margin(kTol));
}

TEST_CASE("exp and log of SE(3) are inverse", "[core][se3]") {
  Vector6d xi;
  xi << 1.5, -0.3, 0.7, 0.4, -0.9, 1.2;
  CHECK((logSE3(expSE3(xi)) - xi).norm() < 1e-9);
  Vector6d small = Vector6d::Constant(1e-10);
  CHECK((logSE3(expSE3(small)) - small).norm() < 1e-12);
}

TEST_CASE("frame composition T_a_c = T_a_b * T_b_c maps points consistently", "[core][se3]") {
  const Pose3 T_a_b = poseFromXyzRpy(10, 0, 0, 0, 0, M_PI / 2);
  const Pose3 T_b_c = poseFromXyzRpy(1, 0, 0, 0, 0, 0);
  const Eigen::Vector3d p_c(1, 0, 0);
  const Eigen::Vector3d p_a = (T_a_b * T_b_c) * p_c;
  CHECK((p_a - Eigen::Vector3d(10, 2, 0)).norm() < kTol);
}

TEST_CASE("interpolate reaches both ends and the midpoint rotation", "[core][se3]") {
  const Pose3 T0 = poseFromXyzRpy(0, 0, 0, 0, 0, 0);
  const Pose3 T1 = poseFromXyzRpy(2, 4, 0, 0, 0, 1.0);
  CHECK((interpolate(T0, T1, 0.0).matrix() - T0.matrix()).norm() < kTol);
  CHECK((interpolate(T0, T1, 1.0).matrix() - T1.matrix()).norm() < kTol);
  const Pose3 mid = interpolate(T0, T1, 0.5);
  CHECK(rpyFromRotation(mid.linear()).z() == Approx(0.5).margin(kTol));
  CHECK((mid.translation() - Eigen::Vector3d(1, 2, 0)).norm() < kTol);
}

TEST_CASE("composeCovariance matches a Monte-Carlo estimate", "[core][se3]") {
  // Right-perturbation model: T = T_nominal * exp(xi). Reference: sample both factors.
  const Pose3 T_a_b = poseFromXyzRpy(3, 1, 0, 0.05, 0.02, 0.4);
  const Pose3 T_b_c = poseFromXyzRpy(5, -2, 0.5, 0.0, 0.1, -0.6);
  const Matrix6d cov_ab = diagonalCovariance(0.05, 0.01);
  const Matrix6d cov_bc = diagonalCovariance(0.02, 0.005);
  const Matrix6d predicted = composeCovariance(T_b_c, cov_ab, cov_bc);

  std::mt19937 rng(7);
  std::normal_distribution<double> n01;
  const Eigen::LLT<Matrix6d> L_ab(cov_ab), L_bc(cov_bc);
  const int kSamples = 20000;
  Matrix6d empirical = Matrix6d::Zero();
  const Pose3 nominal = T_a_b * T_b_c;
  for (int i = 0; i < kSamples; ++i) {
    Vector6d z1, z2;
    for (int k = 0; k < 6; ++k) z1[k] = n01(rng), z2[k] = n01(rng);
    const Pose3 T = (T_a_b * expSE3(L_ab.matrixL() * z1)) * (T_b_c * expSE3(L_bc.matrixL() * z2));
    const Vector6d e = logSE3(nominal.inverse() * T);
    empirical += e * e.transpose();
  }
  empirical /= kSamples;
  // 5 % relative tolerance on the dominant entries: Monte-Carlo noise ~ sqrt(2/N) ~ 1 %.
  constexpr double kRelTol = 0.05;
  CHECK((empirical - predicted).norm() < kRelTol * predicted.norm());
}
