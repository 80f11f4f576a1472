// GBA element residual (eq. (13) / (14)): the closed-form Jacobians of ElementCost against
// central differences through the quaternion manifolds GBA uses (6 DOF and yaw only), and its
// residual against the templated reference.
#include <catch2/catch.hpp>
#include <random>

#include "fusion/element_factor.hpp"
#include "fusion/factors.hpp"
#include "support/test_support.hpp"

using namespace mapfuse::fusion::detail;

namespace {
constexpr double kStep = 1e-6;         // finite-difference step (tangent units)
constexpr double kJacobianTol = 1e-5;  // abs, residuals are O(10) (1/sigma = 20, d ~ 1 m)

struct Setup {
  double ta[3], qa[4], tb[3], qb[4];
  ElementResidual r;
};

Setup randomSetup(std::mt19937& rng, bool plane) {
  std::normal_distribution<double> n(0.0, 1.0);
  Setup s{};
  auto quat = [&](double* q) {
    Eigen::Map<Eigen::Quaterniond> m(q);
    m = Eigen::Quaterniond(mapfuse::test::drawVector<Eigen::Vector4d>(n, rng).normalized());
  };
  for (int i = 0; i < 3; ++i) s.ta[i] = 5 * n(rng), s.tb[i] = 5 * n(rng);
  quat(s.qa);
  quat(s.qb);
  const Eigen::Vector3d dir = mapfuse::test::drawVector<Eigen::Vector3d>(n, rng).normalized();
  s.r = ElementResidual{mapfuse::test::drawVector<Eigen::Vector3d>(n, rng) * 3,
                        mapfuse::test::drawVector<Eigen::Vector3d>(n, rng) * 3, dir, plane, 20.0};
  return s;
}

// Jacobian of the residual w.r.t. one block's tangent space, by central differences through
// the manifold (translation blocks: Euclidean).
Eigen::MatrixXd numericTangentJacobian(const ElementCost& cost, Setup s, int block,
                                       const ceres::Manifold* manifold) {
  double* blocks[4] = {s.ta, s.qa, s.tb, s.qb};
  const int tangent = manifold ? manifold->TangentSize() : 3;
  const int ambient = manifold ? 4 : 3;
  Eigen::MatrixXd J(3, tangent);
  for (int k = 0; k < tangent; ++k) {
    Eigen::Vector3d r[2];
    for (int sgn = 0; sgn < 2; ++sgn) {
      std::vector<double> delta(tangent, 0.0), x(blocks[block], blocks[block] + ambient),
          moved(ambient);
      delta[k] = sgn == 0 ? kStep : -kStep;
      if (manifold) {
        manifold->Plus(x.data(), delta.data(), moved.data());
      } else {
        for (int i = 0; i < 3; ++i) moved[i] = x[i] + delta[i];
      }
      double* params[4] = {s.ta, s.qa, s.tb, s.qb};
      params[block] = moved.data();
      cost.Evaluate(params, r[sgn].data(), nullptr);
    }
    J.col(k) = (r[0] - r[1]) / (2 * kStep);
  }
  return J;
}

void checkJacobians(const Setup& s, const ceres::Manifold& manifold) {
  const ElementCost cost(s.r);
  const double* params[4] = {s.ta, s.qa, s.tb, s.qb};
  Eigen::Matrix<double, 3, 3, Eigen::RowMajor> Jta, Jtb;
  Eigen::Matrix<double, 3, 4, Eigen::RowMajor> Jqa, Jqb;
  double* jac[4] = {Jta.data(), Jqa.data(), Jtb.data(), Jqb.data()};
  Eigen::Vector3d res;
  REQUIRE(cost.Evaluate(params, res.data(), jac));
  for (int block = 0; block < 4; ++block) {
    const bool rot = block % 2 == 1;
    Eigen::MatrixXd analytic;
    if (rot) {
      Eigen::Matrix<double, 4, Eigen::Dynamic, Eigen::RowMajor> P(4, manifold.TangentSize());
      manifold.PlusJacobian(block == 1 ? s.qa : s.qb, P.data());
      analytic = (block == 1 ? Jqa : Jqb) * P;
    } else {
      analytic = block == 0 ? Eigen::MatrixXd(Jta) : Eigen::MatrixXd(Jtb);
    }
    const Eigen::MatrixXd numeric =
        numericTangentJacobian(cost, s, block, rot ? &manifold : nullptr);
    INFO("block " << block << " plane " << s.r.plane << "\nanalytic\n"
                  << analytic << "\nnumeric\n"
                  << numeric);
    CHECK((analytic - numeric).cwiseAbs().maxCoeff() < kJacobianTol);
  }
}
}  // namespace

TEST_CASE("GBA element residual: closed-form Jacobians match central differences") {
  std::mt19937 rng(7);
  const ceres::EigenQuaternionManifold full;
  const ceres::AutoDiffManifold<YawPlus, 4, 1> yaw;
  for (int trial = 0; trial < 20; ++trial)
    for (bool plane : {false, true}) {
      const Setup s = randomSetup(rng, plane);
      checkJacobians(s, full);
      checkJacobians(s, yaw);
      // the residual itself equals the templated reference
      const double* params[4] = {s.ta, s.qa, s.tb, s.qb};
      Eigen::Vector3d analytic, reference;
      ElementCost(s.r).Evaluate(params, analytic.data(), nullptr);
      s.r(s.ta, s.qa, s.tb, s.qb, reference.data());
      CHECK((analytic - reference).norm() < 1e-12);
    }
}

TEST_CASE("yaw-only manifold turns about the world's up axis and keeps roll and pitch") {
  const ceres::AutoDiffManifold<YawPlus, 4, 1> yaw;
  const Eigen::Quaterniond q =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                         Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitY()) *
                         Eigen::AngleAxisd(-0.04, Eigen::Vector3d::UnitX()));
  const double delta = 0.2;
  Eigen::Quaterniond out;
  yaw.Plus(q.coeffs().data(), &delta, out.coeffs().data());
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  // the body's view of "up" (its tilt) is unchanged, its heading turned by delta
  CHECK((out.conjugate() * up - q.conjugate() * up).norm() < 1e-12);
  const Eigen::Vector3d fwd_q = q * Eigen::Vector3d::UnitX(),
                        fwd_o = out * Eigen::Vector3d::UnitX();
  CHECK(std::atan2(fwd_o.y(), fwd_o.x()) - std::atan2(fwd_q.y(), fwd_q.x()) ==
        Approx(delta).margin(1e-12));
  double back = 0;
  yaw.Minus(out.coeffs().data(), q.coeffs().data(), &back);
  CHECK(back == Approx(delta).margin(1e-12));
}
