#include "mapfuse/sim/lsm_observer.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "draw_order.hpp"
#include "mapfuse/core/voxel_grid.hpp"

namespace mapfuse::sim {

namespace {
/// Points of a piece from which pointsNear indexes them by cell (shorter pieces are visited
/// whole: a dash, an arrow, a stop line).
constexpr std::size_t kIndexedPoints = 64;
}  // namespace

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
      PointCells cells(p.points, cell_);
      for (int64_t c : cells.cells()) grid_[c].push_back(id);
      point_cells_.push_back(p.points.size() < kIndexedPoints ? PointCells() : std::move(cells));
      pieces_.push_back(std::move(p));
    }
}

std::vector<uint32_t> PieceIndex::pointsNear(int pi, const Eigen::Vector3d& c,
                                             double radius) const {
  const std::size_t n = pieces_[static_cast<std::size_t>(pi)].points.size();
  if (n >= kIndexedPoints) return point_cells_[static_cast<std::size_t>(pi)].near(c, radius);
  std::vector<uint32_t> all(n);  // a short piece: all of it
  for (std::size_t k = 0; k < n; ++k) all[k] = static_cast<uint32_t>(k);
  return all;
}

std::vector<int> PieceIndex::near(const Eigen::Vector3d& c, double radius) const {
  std::set<int> out;
  voxel_grid::forEachCell2d(c.x() - radius, c.y() - radius, c.x() + radius, c.y() + radius, cell_,
                            [&](int64_t x, int64_t y) {
                              const auto it = grid_.find(voxel_grid::cellKey2d(x, y));
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

namespace {

/// Observes one drive's LSM (observeLsm): the state shared by the steps, one random stream for
/// the observations (drawn in keyframe, piece, run order) and one for the partly seen stop lines.
class LsmObserver {
 public:
  LsmObserver(const World& world, const PieceIndex& index, const Drive& d, const SimCamera& camera,
              const ObservationParams& P, const DriveParams& DP, uint64_t seed)
      : world_(world),
        index_(index),
        d_(d),
        camera_(camera),
        P_(P),
        DP_(DP),
        seed_(seed),
        rng_(seed),
        cam_(camera.T_body_cam().translation()),
        frame_step_(d.speed / DP.camera_rate),
        x_near_(cam_.x() + camera.params().min_range),
        edge_slope_((0.5 * camera.params().width - P.ground_edge_margin_px) / camera.params().fx) {}

  ObservedDrive run() {
    Lsm& lsm = out_.lsm;
    lsm.drive_id = d_.drive_id;
    lsm.vehicle_id = d_.vehicle_id;
    lsm.frame = LsmFrame::kOdom;
    for (const auto& g : d_.gps) lsm.gps.push_back(g.fix);
    out_.keyframe_samples =
        selectKeyframeSamples(d_, DP_.camera_rate, DP_.imu_rate, P_.keyframe_spacing);
    for (std::size_t j = 0; j < out_.keyframe_samples.size(); ++j) observeKeyframe(j);
    observePartialStopLines();
    return std::move(out_);
  }

 private:
  /// A keyframe's ground window [x0, x0 + win) and aerial window [a0, a0 + win), body x.
  struct Window {
    std::size_t j = 0;
    double win = 0.0, x0 = 0.0, x1 = 0.0, a0 = 0.0, a1 = 0.0;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< ENU, of the pieces' query (near)
    double radius = 0.0;                               ///< m
  };
  /// Stop lines whose centre never enters this drive's view (a crossing road's stop line while
  /// the vehicle turns) are still seen in part: the longest visible run, by the solid-line rule
  /// per point, kept per piece and observed once after the drive when the whole line never was.
  struct PartialRun {
    std::size_t keyframe = 0;
    std::vector<Eigen::Vector3d> body;
    double length = 0.0;
  };

  double U(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }

  /// Start of the ground window for a point at lateral offset y: x_near, or, beside the road,
  /// the distance at which the image first holds it (pinhole: |y - y_cam| / depth <= half
  /// width / fx).
  double groundStart(double y) const {
    if (P_.ground_edge_margin_px <= 0 || edge_slope_ <= 0) return x_near_;
    return std::max(x_near_, cam_.x() + std::abs(y - cam_.y()) / edge_slope_);
  }

  /// In the ground window at this keyframe and in the image.
  bool groundVisible(const Eigen::Vector3d& b, double win) const {
    const double g0 = groundStart(b.y());
    return b.x() >= g0 && b.x() < g0 + win && std::abs(b.y()) <= P_.lateral_range &&
           camera_.sees(b, 1.0);
  }

  void addElement(Element e) {
    e.id = next_element_++;
    out_.lsm.elements.push_back(std::move(e));
  }

  /// Noisy copy of body-frame points: a common error per element plus per-point white noise.
  void noisyFrom(std::mt19937_64& g, Element& e, const std::vector<Eigen::Vector3d>& pts,
                 bool aerial) {
    std::vector<Eigen::Matrix3d> covs;
    for (const auto& p : pts) {
      const double r = (p - cam_).head<2>().norm();
      const double along = aerial ? P_.aerial_sigma_base + P_.aerial_sigma_range_quad * r * r
                                  : P_.ground_sigma_base + P_.ground_sigma_range_quad * r * r;
      const double base = aerial ? P_.aerial_sigma_base : P_.ground_sigma_base;
      covs.push_back(pointCovariance(p, cam_, along, base + P_.ground_sigma_angular * r, base));
    }
    Eigen::Matrix3d mean_cov = Eigen::Matrix3d::Zero();
    for (const auto& c : covs) mean_cov += c / static_cast<double>(covs.size());
    const Eigen::Vector3d z0 = drawVector3(N01_, g);
    const Eigen::Vector3d common =
        std::sqrt(P_.correlated_fraction) *
        Eigen::Vector3d(Eigen::Matrix3d(Eigen::LLT<Eigen::Matrix3d>(mean_cov).matrixL()) * z0);
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const Eigen::Vector3d zi = drawVector3(N01_, g);
      e.points_body.push_back(
          pts[i] + common +
          std::sqrt(1.0 - P_.correlated_fraction) *
              Eigen::Vector3d(Eigen::Matrix3d(Eigen::LLT<Eigen::Matrix3d>(covs[i]).matrixL()) *
                              zi));
      e.covariances.push_back(covs[i]);
    }
  }

  int observationsAt(const Eigen::Vector3d& first, double win) const {
    const double r = (first - cam_).head<2>().norm();
    return std::clamp(
        static_cast<int>((camera_.params().max_range - r + win) / std::max(0.1, frame_step_)), 1,
        1000);
  }

  void observeKeyframe(std::size_t j) {
    const auto& kfs = out_.keyframe_samples;
    const std::size_t k = kfs[j];
    Keyframe kf;
    kf.id = static_cast<int64_t>(j);
    kf.stamp = d_.stamps[k];
    kf.T_frame_body = d_.odom[k];
    kf.covariance = diagonalCovariance(0.02 + DP_.wheel_scale_sigma * d_.distance[k],
                                       0.001 + DP_.gyro_bias_sigma * d_.stamps[k]);
    out_.lsm.keyframes.push_back(kf);
    const Pose3& T = d_.truth[k];
    Window w;
    w.j = j;
    w.win = j + 1 < kfs.size() ? d_.distance[kfs[j + 1]] - d_.distance[k] : P_.keyframe_spacing;
    w.x0 = x_near_, w.x1 = x_near_ + w.win;
    w.a0 = x_near_ + P_.aerial_window_offset, w.a1 = w.a0 + w.win;
    const double x_far = std::max(w.a1, groundStart(P_.lateral_range + std::abs(cam_.y())) + w.win);
    const Eigen::Vector3d centre = T * Eigen::Vector3d(0.5 * (w.x0 + x_far), 0, 0);
    const double radius = std::hypot(0.5 * (x_far - w.x0), P_.lateral_range) + 2.0;
    const Pose3 Tinv = T.inverse();
    w.centre = centre, w.radius = radius;
    for (int pi : index_.near(centre, radius)) observePiece(pi, kf.id, Tinv, w);
    falsePositive(kf.id, w);
  }

  /// One piece of a true element at one keyframe: its visible runs (a solid line's stretches in
  /// the window; any other element whole when its centre is seen), each missed or observed.
  void observePiece(int pi, int64_t kf_id, const Pose3& Tinv, const Window& w) {
    const auto& piece = index_.pieces()[pi];
    const MapInstance& m = world_.truth.instances[piece.instance];
    const GeometryKind kind = geometryKind(m.cls);
    const bool aerial = kind == GeometryKind::kPoint || m.cls == CrowdClass::kTrafficSign;
    Element e;
    e.cls = m.cls;
    e.attributes = m.attributes;
    e.anchor = kf_id;
    e.truth_id = m.id;
    e.height = m.height;
    e.confidence = U(0.7, 1.0);
    std::vector<std::vector<Eigen::Vector3d>> runs;
    if (m.cls == CrowdClass::kLaneLine && m.attributes.style != LineStyle::kDashed) {
      runs = solidRuns(piece.points, index_.pointsNear(pi, w.centre, w.radius), Tinv, w.win);
    } else {
      std::vector<Eigen::Vector3d> pts;
      for (const auto& q : piece.points) pts.push_back(Tinv * q);
      const Eigen::Vector3d c = Tinv * piece.centroid;
      const double lo = aerial ? w.a0 : groundStart(c.y()), hi = lo + w.win;
      const Eigen::Vector3d key_point = kind == GeometryKind::kPoint ? pts[0] : c;
      const bool centre_seen = c.x() >= lo && c.x() < hi && std::abs(c.y()) <= P_.lateral_range &&
                               camera_.sees(key_point, 1.0);
      if (m.cls == CrowdClass::kStopLine && !centre_seen && P_.partial_stop_line_min_length > 0)
        keepPartialRun(pi, pts, w);
      if (!centre_seen) return;
      if (m.cls == CrowdClass::kStopLine) whole_.insert(pi);
      runs.push_back(pts);
    }
    for (const auto& run : runs) {
      if (run.size() < 2 && kind == GeometryKind::kLine) continue;
      if (U(0, 1) < P_.miss_probability) {
        ++out_.stats.missed;
        continue;
      }
      Element copy = e;
      noisyFrom(rng_, copy, run, aerial);
      copy.observations = observationsAt(run.front(), w.win);
      if (kind == GeometryKind::kPoint) copy.height = m.height * (1.0 + 0.03 * N01_(rng_));
      addElement(std::move(copy));
      ++out_.stats.elements;
    }
  }

  /// A solid line's visible runs inside the ground window, from the points `near` (ascending
  /// indices; a point left out lies outside the window's cells, so it ends a run as an
  /// invisible one does).
  std::vector<std::vector<Eigen::Vector3d>> solidRuns(const std::vector<Eigen::Vector3d>& points,
                                                      const std::vector<uint32_t>& near,
                                                      const Pose3& Tinv, double win) const {
    std::vector<std::vector<Eigen::Vector3d>> runs;
    std::vector<Eigen::Vector3d> run;
    uint32_t next = 0;  // the index that continues the run
    for (const uint32_t k : near) {
      if (k != next && !run.empty()) {
        runs.push_back(run);
        run.clear();
      }
      next = k + 1;
      const Eigen::Vector3d b = Tinv * points[k];
      if (groundVisible(b, win)) {
        run.push_back(b);
      } else if (!run.empty()) {
        runs.push_back(run);
        run.clear();
      }
    }
    if (!run.empty()) runs.push_back(run);
    return runs;
  }

  /// A stop line whose centre is not seen: its longest visible run, kept if it beats the
  /// piece's best so far.
  void keepPartialRun(int pi, const std::vector<Eigen::Vector3d>& pts, const Window& w) {
    std::vector<Eigen::Vector3d> run, best;
    double best_length = 0;
    auto close = [&] {
      const double l = run.size() >= 2 ? (run.back() - run.front()).head<2>().norm() : 0.0;
      if (l > best_length) best_length = l, best = run;
      run.clear();
    };
    for (const auto& b : pts) {
      if (groundVisible(b, w.win))
        run.push_back(b);
      else
        close();
    }
    close();
    PartialRun& pr = partial_[pi];
    if (best_length >= P_.partial_stop_line_min_length && best_length > pr.length)
      pr = PartialRun{w.j, best, best_length};
  }

  /// False positives along this keyframe's stretch: a short dashed line or a pole.
  void falsePositive(int64_t kf_id, const Window& w) {
    if (!(U(0, 1) < P_.false_positives_per_km * w.win / 1000.0)) return;
    Element f;
    f.anchor = kf_id;
    f.truth_id = -1;
    f.confidence = U(0.3, 0.6);
    const double x = U(w.x0, w.x1);
    if (U(0, 1) < 0.5) {
      f.cls = CrowdClass::kLaneLine;
      f.attributes = {LineStyle::kDashed, LineColor::kWhite};
      const double y = U(-P_.lateral_range, P_.lateral_range);
      std::vector<Eigen::Vector3d> pts;
      for (double s = 0; s <= 3.0; s += P_.point_spacing)
        pts.push_back(Eigen::Vector3d(x + s, y, 0.0));
      noisyFrom(rng_, f, pts, false);
    } else {
      f.cls = CrowdClass::kPole;
      f.height = U(2.0, 6.0);
      const double side = U(0, 1) < 0.5 ? -1 : 1;  // drawn first (draw_order.hpp)
      noisyFrom(rng_, f, {Eigen::Vector3d(x, side * U(5.0, P_.lateral_range), 0.0)}, true);
    }
    addElement(std::move(f));
    ++out_.stats.false_positives;
  }

  /// The partly seen stop lines, from their own random stream (the observations above, and so
  /// every LSM of a simulation without such stop lines, stay as they were).
  void observePartialStopLines() {
    std::mt19937_64 prng(seed_ ^ 0x5a17c0de5a17c0deull);
    for (const auto& [pi, pr] : partial_) {
      if (whole_.count(pi) || pr.body.empty()) continue;
      const MapInstance& m = world_.truth.instances[index_.pieces()[pi].instance];
      if (std::uniform_real_distribution<double>(0, 1)(prng) < P_.miss_probability) {
        ++out_.stats.missed;
        continue;
      }
      Element e;
      e.cls = m.cls;
      e.attributes = m.attributes;
      e.anchor = out_.lsm.keyframes[pr.keyframe].id;
      e.truth_id = m.id;
      e.confidence = std::uniform_real_distribution<double>(0.7, 1.0)(prng);
      noisyFrom(prng, e, pr.body, false);
      e.observations = observationsAt(pr.body.front(), P_.keyframe_spacing);
      addElement(std::move(e));
      ++out_.stats.elements;
      ++out_.stats.partial_stop_lines;
    }
  }

  const World& world_;
  const PieceIndex& index_;
  const Drive& d_;
  const SimCamera& camera_;
  const ObservationParams& P_;
  const DriveParams& DP_;
  const uint64_t seed_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> N01_{0.0, 1.0};
  const Eigen::Vector3d cam_;
  const double frame_step_;  ///< m between camera frames
  const double x_near_;
  const double edge_slope_;
  ObservedDrive out_;
  int64_t next_element_ = 0;
  std::map<int, PartialRun> partial_;
  std::set<int> whole_;
};

}  // namespace

ObservedDrive observeLsm(const World& world, const PieceIndex& index, const Drive& d,
                         const SimCamera& camera, const ObservationParams& P, const DriveParams& DP,
                         uint64_t seed) {
  return LsmObserver(world, index, d, camera, P, DP, seed).run();
}

}  // namespace mapfuse::sim
