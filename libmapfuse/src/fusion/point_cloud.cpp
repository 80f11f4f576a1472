#include "mapfuse/fusion/point_cloud.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <utility>

#include "mapfuse/core/error.hpp"
#include "mapfuse/fusion/voxel_hash.hpp"

namespace mapfuse::fusion {

namespace {
void checkFields(const Cloud& c, const char* what) {
  if (!c.covariances.empty() && c.covariances.size() != c.points.size())
    throw InputError(std::string(what) + ": covariances and points differ in size");
  if (!c.labels.empty() && c.labels.size() != c.points.size())
    throw InputError(std::string(what) + ": labels and points differ in size");
}
}  // namespace

Cloud voxelDownsample(const Cloud& in, double voxel_size) {
  if (!(voxel_size > 0.0)) throw InputError("voxelDownsample: voxel_size must be > 0");
  checkFields(in, "voxelDownsample");
  const double inv = 1.0 / voxel_size;
  const std::size_t n = in.size();
  std::vector<std::pair<uint64_t, int>> keyed(n);
  for (std::size_t i = 0; i < n; ++i) keyed[i] = {voxelKey(in.points[i], inv), int(i)};
  std::sort(keyed.begin(), keyed.end());
  Cloud out;
  const bool has_cov = !in.covariances.empty(), has_label = !in.labels.empty();
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d csum = Eigen::Matrix3d::Zero();
    std::array<int, 256> votes{};
    while (j < n && keyed[j].first == keyed[i].first) {
      const int k = keyed[j].second;
      sum += in.points[k];
      if (has_cov) csum += in.covariances[k];
      if (has_label) ++votes[in.labels[k]];
      ++j;
    }
    const double count = double(j - i);
    out.points.push_back(sum / count);
    if (has_cov) out.covariances.push_back(csum / count);
    if (has_label)
      out.labels.push_back(uint8_t(std::max_element(votes.begin(), votes.end()) - votes.begin()));
    i = j;
  }
  return out;
}

Eigen::Matrix3d planeRegularized(const Eigen::Matrix3d& sample_cov, double eps) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(sample_cov);
  const Eigen::Vector3d values(eps, 1.0, 1.0);  // eigenvalues come in increasing order
  return es.eigenvectors() * values.asDiagonal() * es.eigenvectors().transpose();
}

void estimateCovariances(Cloud& cloud, int num_neighbors, double neighbor_cell_size) {
  if (num_neighbors < 3) throw InputError("estimateCovariances: num_neighbors must be >= 3");
  if (!(neighbor_cell_size > 0.0))
    throw InputError("estimateCovariances: neighbor_cell_size must be > 0");
  const VoxelIndex index(cloud.points, neighbor_cell_size);
  const int n = int(cloud.size());
  cloud.covariances.resize(n);
#pragma omp parallel
  {
    std::vector<int> idx(num_neighbors);
    std::vector<double> d2(num_neighbors);
#pragma omp for schedule(static)
    for (int i = 0; i < n; ++i) {
      const int found = index.knn(cloud.points[i], num_neighbors, idx.data(), d2.data());
      if (found < 3) {
        cloud.covariances[i] = Eigen::Matrix3d::Identity();
        continue;
      }
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (int k = 0; k < found; ++k) mean += cloud.points[idx[k]];
      mean /= found;
      Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
      for (int k = 0; k < found; ++k) {
        const Eigen::Vector3d d = cloud.points[idx[k]] - mean;
        cov += d * d.transpose();
      }
      cloud.covariances[i] = planeRegularized(cov / found);
    }
  }
}

Cloud transformCloud(const Cloud& in, const Pose3& T) {
  Cloud out;
  out.points.reserve(in.size());
  for (const auto& p : in.points) out.points.push_back(T * p);
  const Eigen::Matrix3d R = T.linear();
  out.covariances.reserve(in.covariances.size());
  for (const auto& c : in.covariances) out.covariances.push_back(R * c * R.transpose());
  out.labels = in.labels;
  return out;
}

void appendCloud(Cloud& a, const Cloud& b) {
  const bool a_empty = a.empty();
  if (!a_empty &&
      (a.covariances.empty() != b.covariances.empty() || a.labels.empty() != b.labels.empty()))
    throw InputError("appendCloud: clouds carry different optional fields");
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  a.covariances.insert(a.covariances.end(), b.covariances.begin(), b.covariances.end());
  a.labels.insert(a.labels.end(), b.labels.begin(), b.labels.end());
}

}  // namespace mapfuse::fusion
