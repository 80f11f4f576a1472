#include "scan_normals.hpp"

#include <Eigen/Eigenvalues>

#include "mapfuse/core/error.hpp"
#include "mapfuse/fusion/voxel_hash.hpp"

namespace mapfuse::lidar {

ScanNormals::ScanNormals(const std::vector<Eigen::Vector3d>& points, int k, double cell)
    : points_(points), k_(k) {
  if (k < 3) throw InputError("estimateNormals: k must be >= 3");
  if (!(cell > 0)) throw InputError("estimateNormals: cell must be > 0");
  index_ = fusion::VoxelIndex(points, cell);
}

Eigen::Vector3d ScanNormals::at(std::size_t i) const {
  int idx[32];
  double d2[32];
  const int found = index_.knn(points_[i], std::min(k_, 32), idx, d2);
  if (found < 3) return Eigen::Vector3d::Zero();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int j = 0; j < found; ++j) mean += points_[static_cast<std::size_t>(idx[j])];
  mean /= found;
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (int j = 0; j < found; ++j) {
    const Eigen::Vector3d d = points_[static_cast<std::size_t>(idx[j])] - mean;
    C += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);
  if (!(es.eigenvalues()(1) > 0.01 * es.eigenvalues()(2))) return Eigen::Vector3d::Zero();
  return es.eigenvectors().col(0);  // collinear neighbours (one ring) above: no normal
}

std::vector<Eigen::Vector3d> estimateNormals(const std::vector<Eigen::Vector3d>& points, int k,
                                             double cell) {
  const ScanNormals normals(points, k, cell);
  std::vector<Eigen::Vector3d> out(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) out[i] = normals.at(i);
  return out;
}

}  // namespace mapfuse::lidar
