#include "lane_surface.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <unordered_map>
#include <vector>

#include "mapfuse/core/voxel_grid.hpp"
#include "mapfuse/sim/polyline.hpp"

namespace mapfuse::sim {
namespace {
constexpr double kRadius = 6.0;       // m, samples around a query: the lanes of one carriageway
constexpr double kDeckGap = 1.5;      // m, samples farther in height belong to another deck
constexpr double kSurfaceStep = 1.0;  // m between samples along a lane or a line
constexpr double kMinAcross = 0.25;   // m², least variance across the samples' main axis
constexpr int kMinSamples = 6;        // for a plane

/// Samples in 2-D cells of kRadius (a query reads its cell and the 8 around it).
struct SurfaceSamples {
  std::unordered_map<uint64_t, std::vector<Eigen::Vector3d>> cells;
  static uint64_t key(int64_t ix, int64_t iy) { return voxel_grid::pack(ix, iy, 0); }
  void add(const Eigen::Vector3d& p) {
    cells[key(int64_t(std::floor(p.x() / kRadius)), int64_t(std::floor(p.y() / kRadius)))]
        .push_back(p);
  }
  void addLine(const Polyline& line) {
    if (line.size() < 2) return;
    for (const auto& p : resample(line, kSurfaceStep)) add(p);
  }
  double height(const Eigen::Vector3d& q) const {
    std::vector<Eigen::Vector3d> near;
    voxel_grid::forEachCell2d(
        q.x() - kRadius, q.y() - kRadius, q.x() + kRadius, q.y() + kRadius, kRadius,
        [&](int64_t ix, int64_t iy) {
          const auto it = cells.find(key(ix, iy));
          if (it == cells.end()) return;
          for (const auto& p : it->second)
            if ((p - q).head<2>().norm() <= kRadius && std::abs(p.z() - q.z()) <= kDeckGap)
              near.push_back(p);
        });
    if (near.empty()) return q.z();
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& p : near) mean += p;
    mean /= double(near.size());
    if (int(near.size()) < kMinSamples) return mean.z();
    // Plane z = mean.z + g . (xy - mean.xy), least squares; needs extent on both axes.
    Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
    Eigen::Vector2d b = Eigen::Vector2d::Zero();
    for (const auto& p : near) {
      const Eigen::Vector2d d = (p - mean).head<2>();
      A += d * d.transpose();
      b += d * (p.z() - mean.z());
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(A / double(near.size()));
    if (eig.eigenvalues()(0) < kMinAcross) return mean.z();
    const Eigen::Vector2d g = A.ldlt().solve(b);
    return mean.z() + g.dot((q - mean).head<2>());
  }
};
}  // namespace

std::function<double(const Eigen::Vector3d&)> laneSurface(const World& world) {
  auto samples = std::make_shared<SurfaceSamples>();
  for (const Lane& lane : world.lanes) samples->addLine(lane.centerline);
  for (const MapInstance& m : world.truth.instances)
    if (m.cls == CrowdClass::kLaneLine) samples->addLine(m.points);
  return [samples](const Eigen::Vector3d& q) { return samples->height(q); };
}

}  // namespace mapfuse::sim
