#include "mapfuse/lidar/scan_normals.hpp"

#include <Eigen/Eigenvalues>

#include "mapfuse/core/error.hpp"
#include "mapfuse/fusion/voxel_hash.hpp"

namespace mapfuse::lidar {

std::vector<Eigen::Vector3d> estimateNormals(const std::vector<Eigen::Vector3d>& points, int k,
                                             double cell) {
  if (k < 3) throw InputError("estimateNormals: k must be >= 3");
  if (!(cell > 0)) throw InputError("estimateNormals: cell must be > 0");
  const fusion::VoxelIndex index(points, cell);
  std::vector<Eigen::Vector3d> normals(points.size(), Eigen::Vector3d::Zero());
  std::vector<int> idx(static_cast<std::size_t>(k));
  std::vector<double> d2(static_cast<std::size_t>(k));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int found = index.knn(points[i], k, idx.data(), d2.data());
    if (found < 3) continue;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (int j = 0; j < found; ++j) mean += points[static_cast<std::size_t>(idx[j])];
    mean /= found;
    Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
    for (int j = 0; j < found; ++j) {
      const Eigen::Vector3d d = points[static_cast<std::size_t>(idx[j])] - mean;
      C += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);
    if (!(es.eigenvalues()(1) > 0.01 * es.eigenvalues()(2))) continue;  // collinear: a ring
    normals[i] = es.eigenvectors().col(0);
  }
  return normals;
}

}  // namespace mapfuse::lidar
