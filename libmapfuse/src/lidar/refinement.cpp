// Vehicle-trace removal (Jeong et al. 2018, §2.2); the K-nearest filter is in knn_filter.cpp.
#include "mapfuse/lidar/refinement.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <deque>
#include <unordered_map>

#include "mapfuse/core/error.hpp"

namespace mapfuse::lidar {

std::vector<uint8_t> vehicleTraceFilter(const SemanticVoxelMap& map, const VehicleTraceSettings& s,
                                        VehicleTraceStats* stats) {
  if (!(s.eps > 0) || s.min_points < 1) throw InputError("vehicle trace DBSCAN: bad eps/minPts");
  const auto& vox = map.voxels();
  const double vs = map.voxelSize();
  std::vector<uint8_t> keep(vox.size(), 1);
  VehicleTraceStats st;
  // 2D cells (voxel resolution) of the vehicle voxels, in first-seen order.
  std::unordered_map<uint64_t, int> cell_of;
  std::vector<Eigen::Vector2i> cells;
  std::vector<std::vector<uint32_t>> members;
  auto key2 = [](int x, int y) { return (uint64_t(uint32_t(x)) << 32) | uint64_t(uint32_t(y)); };
  for (std::size_t i = 0; i < vox.size(); ++i) {
    if (vox[i].label != static_cast<uint8_t>(LidarClass::kVehicle)) continue;
    ++st.vehicle_voxels;
    const VoxelCoord c = unpackKey(vox[i].key);
    auto [it, inserted] = cell_of.emplace(key2(c.x, c.y), static_cast<int>(cells.size()));
    if (inserted) {
      cells.emplace_back(c.x, c.y);
      members.emplace_back();
    }
    members[it->second].push_back(static_cast<uint32_t>(i));
  }
  const int reach = static_cast<int>(std::floor(s.eps / vs));
  const double eps2 = (s.eps / vs) * (s.eps / vs);
  auto neighbours = [&](int ci, std::vector<int>& out) {
    out.clear();
    for (int dx = -reach; dx <= reach; ++dx)
      for (int dy = -reach; dy <= reach; ++dy) {
        if (dx * dx + dy * dy > eps2) continue;
        const auto it = cell_of.find(key2(cells[ci].x() + dx, cells[ci].y() + dy));
        if (it != cell_of.end()) out.push_back(it->second);
      }
  };
  // DBSCAN (Ester et al. 1996) over the cells.
  std::vector<int> cluster(cells.size(), -1);  // -1 unvisited, -2 noise
  std::vector<int> nb, nb2;
  int num = 0;
  for (std::size_t ci = 0; ci < cells.size(); ++ci) {
    if (cluster[ci] != -1) continue;
    neighbours(static_cast<int>(ci), nb);
    if (static_cast<int>(nb.size()) < s.min_points) {
      cluster[ci] = -2;
      continue;
    }
    const int id = num++;
    cluster[ci] = id;
    std::deque<int> queue(nb.begin(), nb.end());
    while (!queue.empty()) {
      const int q = queue.front();
      queue.pop_front();
      if (cluster[q] == -2) cluster[q] = id;  // border point
      if (cluster[q] != -1) continue;
      cluster[q] = id;
      neighbours(q, nb2);
      if (static_cast<int>(nb2.size()) >= s.min_points)
        queue.insert(queue.end(), nb2.begin(), nb2.end());
    }
  }
  st.clusters = static_cast<std::size_t>(num);
  // Size and length (extent along the principal axis) of each cluster.
  std::vector<std::vector<int>> cells_of(num);
  for (std::size_t ci = 0; ci < cells.size(); ++ci)
    if (cluster[ci] >= 0) cells_of[cluster[ci]].push_back(static_cast<int>(ci));
  for (int id = 0; id < num; ++id) {
    std::size_t nvox = 0;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (int ci : cells_of[id]) {
      nvox += members[ci].size();
      mean += cells[ci].cast<double>();
    }
    mean /= static_cast<double>(cells_of[id].size());
    Eigen::Matrix2d C = Eigen::Matrix2d::Zero();
    for (int ci : cells_of[id]) {
      const Eigen::Vector2d d = cells[ci].cast<double>() - mean;
      C += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(C);
    const Eigen::Vector2d axis = es.eigenvectors().col(1);
    double lo = 1e300, hi = -1e300;
    for (int ci : cells_of[id]) {
      const double t = axis.dot(cells[ci].cast<double>());
      lo = std::min(lo, t);
      hi = std::max(hi, t);
    }
    const double length = (hi - lo + 1.0) * vs;
    if (nvox > s.max_voxels || length > s.max_length) {
      ++st.removed_clusters;
      st.removed_voxels += nvox;
      for (int ci : cells_of[id])
        for (uint32_t v : members[ci]) keep[v] = 0;
    }
  }
  if (stats) *stats = st;
  return keep;
}

}  // namespace mapfuse::lidar
