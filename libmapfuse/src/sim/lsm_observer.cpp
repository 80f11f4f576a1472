#include "mapfuse/sim/lsm_observer.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "draw_order.hpp"
#include "mapfuse/core/voxel_grid.hpp"

namespace mapfuse::sim {

PieceIndex::PieceIndex(const World& world, double point_spacing) {
  const auto& inst = world.truth.instances;
  for (std::size_t i = 0; i < inst.size(); ++i)
    for (auto& pts : observablePieces(inst[i], world.dashes, point_spacing)) {
      Piece p;
      p.instance = i;
      p.centroid = Eigen::Vector3d::Zero();
      for (const auto& q : pts) p.centroid += q / static_cast<double>(pts.size());
      p.points = std::move(pts);
      const int id = static_cast<int>(pieces_.size());
      std::set<int64_t> cells;
      for (const auto& q : p.points)
        cells.insert(key(static_cast<int64_t>(std::floor(q.x() / cell_)),
                         static_cast<int64_t>(std::floor(q.y() / cell_))));
      for (int64_t c : cells) grid_[c].push_back(id);
      pieces_.push_back(std::move(p));
    }
}

std::vector<int> PieceIndex::near(const Eigen::Vector3d& c, double radius) const {
  std::set<int> out;
  voxel_grid::forEachCell2d(c.x() - radius, c.y() - radius, c.x() + radius, c.y() + radius, cell_,
                            [&](int64_t x, int64_t y) {
                              const auto it = grid_.find(key(x, y));
                              if (it != grid_.end())
                                out.insert(it->second.begin(), it->second.end());
                            });
  return {out.begin(), out.end()};
}

std::vector<std::size_t> selectKeyframeSamples(const Drive& d, double camera_rate, double imu_rate,
                                               double spacing) {
  const std::size_t every = std::max<std::size_t>(1, std::lround(imu_rate / camera_rate));
  std::vector<std::size_t> kf{0};
  double travelled = 0.0;
  for (std::size_t k = every; k < d.odom.size(); k += every) {
    travelled += (d.odom[k].translation() - d.odom[k - every].translation()).norm();
    if (travelled >= spacing) {
      kf.push_back(k);
      travelled = 0.0;
    }
  }
  if (kf.back() + every < d.odom.size()) kf.push_back((d.odom.size() - 1) / every * every);
  return kf;
}

namespace {

/// Covariance of a body-frame point: along-ray / across-ray / vertical sigmas rotated into body.
Eigen::Matrix3d pointCovariance(const Eigen::Vector3d& p_body, const Eigen::Vector3d& cam,
                                double sigma_along, double sigma_across, double sigma_z) {
  Eigen::Vector3d ray = p_body - cam;
  ray.z() = 0.0;
  const double n = ray.norm();
  const Eigen::Vector3d u = n > 1e-9 ? Eigen::Vector3d(ray / n) : Eigen::Vector3d::UnitX();
  Eigen::Matrix3d R;
  R.col(0) = u;
  R.col(1) = Eigen::Vector3d(-u.y(), u.x(), 0.0);
  R.col(2) = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d s2(sigma_along * sigma_along, sigma_across * sigma_across,
                           sigma_z * sigma_z);
  return R * s2.asDiagonal() * R.transpose();
}

}  // namespace

ObservedDrive observeLsm(const World& world, const PieceIndex& index, const Drive& d,
                         const SimCamera& camera, const ObservationParams& P, const DriveParams& DP,
                         uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> N01(0.0, 1.0);
  auto U = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  ObservedDrive out;
  Lsm& lsm = out.lsm;
  lsm.drive_id = d.drive_id;
  lsm.vehicle_id = d.vehicle_id;
  lsm.frame = LsmFrame::kOdom;
  for (const auto& g : d.gps) lsm.gps.push_back(g.fix);
  out.keyframe_samples = selectKeyframeSamples(d, DP.camera_rate, DP.imu_rate, P.keyframe_spacing);
  const auto& kfs = out.keyframe_samples;
  const Eigen::Vector3d cam = camera.T_body_cam().translation();
  const double frame_step = d.speed / DP.camera_rate;  // m between camera frames
  const double x_near = cam.x() + camera.params().min_range;
  // Start of the ground window for a point at lateral offset y: x_near, or, beside the road, the
  // distance at which the image first holds it (pinhole: |y - y_cam| / depth <= half width / fx).
  const CameraParams& cp = camera.params();
  const double edge_slope = (0.5 * cp.width - P.ground_edge_margin_px) / cp.fx;
  auto groundStart = [&](double y) {
    if (P.ground_edge_margin_px <= 0 || edge_slope <= 0) return x_near;
    return std::max(x_near, cam.x() + std::abs(y - cam.y()) / edge_slope);
  };
  const auto& inst = world.truth.instances;
  int64_t next_element = 0;

  auto addElement = [&](Element e) {
    e.id = next_element++;
    lsm.elements.push_back(std::move(e));
  };
  // Noisy copy of body-frame points: a common error per element plus per-point white noise.
  auto noisyFrom = [&](std::mt19937_64& g, Element& e, const std::vector<Eigen::Vector3d>& pts,
                       bool aerial) {
    std::vector<Eigen::Matrix3d> covs;
    for (const auto& p : pts) {
      const double r = (p - cam).head<2>().norm();
      const double along = aerial ? P.aerial_sigma_base + P.aerial_sigma_range_quad * r * r
                                  : P.ground_sigma_base + P.ground_sigma_range_quad * r * r;
      const double base = aerial ? P.aerial_sigma_base : P.ground_sigma_base;
      covs.push_back(pointCovariance(p, cam, along, base + P.ground_sigma_angular * r, base));
    }
    Eigen::Matrix3d mean_cov = Eigen::Matrix3d::Zero();
    for (const auto& c : covs) mean_cov += c / static_cast<double>(covs.size());
    const Eigen::Vector3d z0 = drawVector3(N01, g);
    const Eigen::Vector3d common =
        std::sqrt(P.correlated_fraction) *
        Eigen::Vector3d(Eigen::Matrix3d(Eigen::LLT<Eigen::Matrix3d>(mean_cov).matrixL()) * z0);
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const Eigen::Vector3d zi = drawVector3(N01, g);
      e.points_body.push_back(
          pts[i] + common +
          std::sqrt(1.0 - P.correlated_fraction) *
              Eigen::Vector3d(Eigen::Matrix3d(Eigen::LLT<Eigen::Matrix3d>(covs[i]).matrixL()) *
                              zi));
      e.covariances.push_back(covs[i]);
    }
  };
  auto noisy = [&](Element& e, const std::vector<Eigen::Vector3d>& pts, bool aerial) {
    noisyFrom(rng, e, pts, aerial);
  };
  // Stop lines whose centre never enters this drive's view (a crossing road's stop line while
  // the vehicle turns) are still seen in part: the longest visible run, by the solid-line rule
  // per point, kept per piece and observed once after the drive when the whole line never was.
  struct PartialRun {
    std::size_t keyframe = 0;
    std::vector<Eigen::Vector3d> body;
    double length = 0.0;
  };
  std::map<int, PartialRun> partial;
  std::set<int> whole;

  for (std::size_t j = 0; j < kfs.size(); ++j) {
    const std::size_t k = kfs[j];
    Keyframe kf;
    kf.id = static_cast<int64_t>(j);
    kf.stamp = d.stamps[k];
    kf.T_frame_body = d.odom[k];
    kf.covariance = diagonalCovariance(0.02 + DP.wheel_scale_sigma * d.distance[k],
                                       0.001 + DP.gyro_bias_sigma * d.stamps[k]);
    lsm.keyframes.push_back(kf);
    const Pose3& T = d.truth[k];
    const Pose3 Tinv = T.inverse();
    const double win =
        j + 1 < kfs.size() ? d.distance[kfs[j + 1]] - d.distance[k] : P.keyframe_spacing;
    const double x0 = x_near, x1 = x_near + win;
    const double a0 = x_near + P.aerial_window_offset, a1 = a0 + win;
    const double x_far = std::max(a1, groundStart(P.lateral_range + std::abs(cam.y())) + win);
    const Eigen::Vector3d centre = T * Eigen::Vector3d(0.5 * (x0 + x_far), 0, 0);
    const double radius = std::hypot(0.5 * (x_far - x0), P.lateral_range) + 2.0;
    for (int pi : index.near(centre, radius)) {
      const auto& piece = index.pieces()[pi];
      const MapInstance& m = inst[piece.instance];
      const GeometryKind kind = geometryKind(m.cls);
      Element e;
      e.cls = m.cls;
      e.attributes = m.attributes;
      e.anchor = kf.id;
      e.truth_id = m.id;
      e.height = m.height;
      e.confidence = U(0.7, 1.0);
      std::vector<std::vector<Eigen::Vector3d>> runs;
      const bool split = m.cls == CrowdClass::kLaneLine && m.attributes.style != LineStyle::kDashed;
      if (split) {  // solid line: the visible runs inside the window
        std::vector<Eigen::Vector3d> run;
        for (const auto& q : piece.points) {
          const Eigen::Vector3d b = Tinv * q;
          const double g0 = groundStart(b.y());
          if (b.x() >= g0 && b.x() < g0 + win && std::abs(b.y()) <= P.lateral_range &&
              camera.sees(b, 1.0)) {
            run.push_back(b);
          } else if (!run.empty()) {
            runs.push_back(run);
            run.clear();
          }
        }
        if (!run.empty()) runs.push_back(run);
      } else {
        const Eigen::Vector3d c = Tinv * piece.centroid;
        const bool aerial = kind == GeometryKind::kPoint || m.cls == CrowdClass::kTrafficSign;
        const double lo = aerial ? a0 : groundStart(c.y()), hi = lo + win;
        std::vector<Eigen::Vector3d> pts;
        for (const auto& q : piece.points) pts.push_back(Tinv * q);
        const Eigen::Vector3d key_point = kind == GeometryKind::kPoint ? pts[0] : c;
        const bool centre_seen = c.x() >= lo && c.x() < hi && std::abs(c.y()) <= P.lateral_range &&
                                 camera.sees(key_point, 1.0);
        if (m.cls == CrowdClass::kStopLine && !centre_seen && P.partial_stop_line_min_length > 0) {
          std::vector<Eigen::Vector3d> run, best;
          double best_length = 0;
          auto close = [&] {
            const double l = run.size() >= 2 ? (run.back() - run.front()).head<2>().norm() : 0.0;
            if (l > best_length) best_length = l, best = run;
            run.clear();
          };
          for (const auto& b : pts) {
            const double g0 = groundStart(b.y());
            if (b.x() >= g0 && b.x() < g0 + win && std::abs(b.y()) <= P.lateral_range &&
                camera.sees(b, 1.0))
              run.push_back(b);
            else
              close();
          }
          close();
          PartialRun& pr = partial[pi];
          if (best_length >= P.partial_stop_line_min_length && best_length > pr.length)
            pr = PartialRun{j, best, best_length};
        }
        if (!centre_seen) continue;
        if (m.cls == CrowdClass::kStopLine) whole.insert(pi);
        runs.push_back(pts);
      }
      for (const auto& run : runs) {
        if (run.size() < 2 && kind == GeometryKind::kLine) continue;
        if (U(0, 1) < P.miss_probability) {
          ++out.stats.missed;
          continue;
        }
        Element copy = e;
        const bool aerial = kind == GeometryKind::kPoint || m.cls == CrowdClass::kTrafficSign;
        noisy(copy, run, aerial);
        const double r = (run.front() - cam).head<2>().norm();
        copy.observations = std::clamp(
            static_cast<int>((camera.params().max_range - r + win) / std::max(0.1, frame_step)), 1,
            1000);
        if (kind == GeometryKind::kPoint) copy.height = m.height * (1.0 + 0.03 * N01(rng));
        addElement(std::move(copy));
        ++out.stats.elements;
      }
    }
    // False positives along this keyframe's stretch.
    if (U(0, 1) < P.false_positives_per_km * win / 1000.0) {
      Element f;
      f.anchor = kf.id;
      f.truth_id = -1;
      f.confidence = U(0.3, 0.6);
      const double x = U(x0, x1);
      if (U(0, 1) < 0.5) {
        f.cls = CrowdClass::kLaneLine;
        f.attributes = {LineStyle::kDashed, LineColor::kWhite};
        const double y = U(-P.lateral_range, P.lateral_range);
        std::vector<Eigen::Vector3d> pts;
        for (double s = 0; s <= 3.0; s += P.point_spacing)
          pts.push_back(Eigen::Vector3d(x + s, y, 0.0));
        noisy(f, pts, false);
      } else {
        f.cls = CrowdClass::kPole;
        f.height = U(2.0, 6.0);
        const double side = U(0, 1) < 0.5 ? -1 : 1;  // drawn first (draw_order.hpp)
        noisy(f, {Eigen::Vector3d(x, side * U(5.0, P.lateral_range), 0.0)}, true);
      }
      addElement(std::move(f));
      ++out.stats.false_positives;
    }
  }
  // The partly seen stop lines, from their own random stream (the observations above, and so
  // every LSM of a simulation without such stop lines, stay as they were).
  std::mt19937_64 prng(seed ^ 0x5a17c0de5a17c0deull);
  for (const auto& [pi, pr] : partial) {
    if (whole.count(pi) || pr.body.empty()) continue;
    const MapInstance& m = inst[index.pieces()[pi].instance];
    if (std::uniform_real_distribution<double>(0, 1)(prng) < P.miss_probability) {
      ++out.stats.missed;
      continue;
    }
    Element e;
    e.cls = m.cls;
    e.attributes = m.attributes;
    e.anchor = lsm.keyframes[pr.keyframe].id;
    e.truth_id = m.id;
    e.confidence = std::uniform_real_distribution<double>(0.7, 1.0)(prng);
    noisyFrom(prng, e, pr.body, false);
    const double r = (pr.body.front() - cam).head<2>().norm();
    e.observations =
        std::clamp(static_cast<int>((camera.params().max_range - r + P.keyframe_spacing) /
                                    std::max(0.1, frame_step)),
                   1, 1000);
    addElement(std::move(e));
    ++out.stats.elements;
    ++out.stats.partial_stop_lines;
  }
  return out;
}

}  // namespace mapfuse::sim
