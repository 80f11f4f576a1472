#include "mapfuse/lidar/cluster_features.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace mapfuse::lidar {

const char* const kClusterFeatureNames[kNumClusterFeatures] = {
    "extent_x",   "extent_y",     "extent_z",   "linearity",   "planarity",
    "scattering", "omnivariance", "anisotropy", "eigenentropy"};

ClusterFeatures clusterFeatures(const std::vector<Eigen::Vector3f>& points,
                                const std::vector<int>& members) {
  ClusterFeatures f{};
  if (members.empty()) return f;
  Eigen::Vector3d lo = points[members[0]].cast<double>(), hi = lo, mean = Eigen::Vector3d::Zero();
  for (int i : members) {
    const Eigen::Vector3d p = points[i].cast<double>();
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    mean += p;
  }
  mean /= static_cast<double>(members.size());
  f[0] = static_cast<float>(hi.x() - lo.x());
  f[1] = static_cast<float>(hi.y() - lo.y());
  f[2] = static_cast<float>(hi.z() - lo.z());
  if (members.size() < 3) return f;
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (int i : members) {
    const Eigen::Vector3d d = points[i].cast<double>() - mean;
    C += d * d.transpose();
  }
  C /= static_cast<double>(members.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C, Eigen::EigenvaluesOnly);
  Eigen::Vector3d ev = es.eigenvalues().cwiseMax(0.0);  // ascending
  const double sum = ev.sum();
  if (!(sum > 1e-12)) return f;
  const double e1 = ev[2] / sum, e2 = ev[1] / sum, e3 = ev[0] / sum;
  f[3] = static_cast<float>((e1 - e2) / e1);           // linearity
  f[4] = static_cast<float>((e2 - e3) / e1);           // planarity
  f[5] = static_cast<float>(e3 / e1);                  // scattering
  f[6] = static_cast<float>(std::cbrt(e1 * e2 * e3));  // omnivariance
  f[7] = static_cast<float>((e1 - e3) / e1);           // anisotropy
  double h = 0;
  for (double e : {e1, e2, e3})
    if (e > 1e-12) h -= e * std::log(e);
  f[8] = static_cast<float>(h);  // eigenentropy
  return f;
}

}  // namespace mapfuse::lidar
