#include "mapfuse/lidar/scan_odometry.hpp"

#include <cmath>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/param_check.hpp"
#include "mapfuse/core/voxel_grid.hpp"
#include "scan_normals.hpp"

namespace mapfuse::lidar {
namespace {

/// The first point of every voxel (kiss-icp's VoxelDownsample), in input order.
std::vector<Eigen::Vector3d> downsample(const std::vector<Eigen::Vector3d>& pts, double voxel) {
  std::size_t cap = 1024;
  while (cap < 2 * pts.size()) cap <<= 1;
  std::vector<uint64_t> table(cap, ~0ull);
  const uint64_t mask = cap - 1;
  const double inv = 1.0 / voxel;
  std::vector<Eigen::Vector3d> out;
  out.reserve(pts.size() / 2);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const uint64_t key = voxel_grid::pointKey(pts[i], inv);
    uint64_t h = voxel_grid::mix(key) & mask;
    bool seen = false;
    while (table[h] != ~0ull) {
      if (table[h] == key) {
        seen = true;
        break;
      }
      h = (h + 1) & mask;
    }
    if (seen) continue;
    table[h] = key;
    out.push_back(pts[i]);
  }
  return out;
}

double modelError(const Pose3& deviation, double max_range) {
  const double theta = Eigen::AngleAxisd(deviation.linear()).angle();
  return deviation.translation().norm() + 2.0 * max_range * std::sin(0.5 * theta);
}

}  // namespace

double sweepFraction(const Eigen::Vector3f& p) {
  return 0.5 * (-std::atan2(double(p.y()), double(p.x())) / M_PI + 1.0);
}

std::vector<Eigen::Vector3d> deskewScan(const std::vector<Eigen::Vector3f>& scan,
                                        const Pose3& motion) {
  // exp((s - 0.5) xi) tabulated in 1024 steps of s: at most 1/2048 of a sweep's motion off.
  constexpr int kSteps = 1024;
  const Vector6d xi = logSE3(motion);
  std::vector<Pose3> table(kSteps + 1);
  for (int k = 0; k <= kSteps; ++k) table[k] = expSE3((double(k) / kSteps - 0.5) * xi);
  std::vector<Eigen::Vector3d> out(scan.size());
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const int k = static_cast<int>(std::lround(sweepFraction(scan[i]) * kSteps));
    out[i] = table[std::clamp(k, 0, kSteps)] * scan[i].cast<double>();
  }
  return out;
}

Pose3 orthonormalized(const Pose3& T) {
  Pose3 out = Pose3::Identity();
  out.linear() = Eigen::Quaterniond(T.linear()).normalized().toRotationMatrix();
  out.translation() = T.translation();
  return out;
}

Pose3 scaleMotion(const Pose3& T, double alpha) {
  return expSE3(alpha * logSE3(T));
}

ScanOdometry::ScanOdometry(const OdometrySettings& s)
    : s_(s), map_([&] {
        param::validate(s);
        param::validate(s.geometry);
        param::validate(s.trust);
        return LocalMapSettings{s.voxel_size, s.max_points_per_voxel, s.max_range};
      }()) {
  model_sse_ = s.initial_threshold * s.initial_threshold;
  model_samples_ = 1;
}

double ScanOdometry::sigma() const {
  return std::sqrt(model_sse_ / model_samples_);
}

void ScanOdometry::insertKeyframe(const std::vector<Eigen::Vector3d>& frame, const Pose3& T) {
  // Normals only of the points the map keeps (once its voxels fill up, few of a keyframe's).
  const ScanNormals normals(frame, s_.normal_neighbors, s_.normal_radius);
  std::vector<Eigen::Vector3d> pts(frame.size());
  for (std::size_t k = 0; k < frame.size(); ++k) pts[k] = T * frame[k];
  const Eigen::Matrix3d R = T.linear();
  map_.update(
      pts, [&](std::size_t i) { return Eigen::Vector3d(R * normals.at(i)); }, T.translation());
  keyframe_ = T;
}

const OdometryStep& ScanOdometry::add(const std::vector<Eigen::Vector3f>& scan, double dt,
                                      const std::vector<uint8_t>* exclude) {
  if (exclude && exclude->size() != scan.size())
    throw InputError("odometry: exclusion mask and scan differ in size");
  const bool first = poses_.empty();
  if (!first && !(dt > 0)) throw InputError("odometry: time between scans must be > 0");
  const bool velocity_known = last_dt_ > 0;

  // Range crop and exclusion; possible road users left out (at a finer spacing than the map's:
  // the vertical gaps that separate a truck from a bridge deck above it must survive).
  const double r2min = s_.min_range * s_.min_range, r2max = s_.max_range * s_.max_range;
  std::vector<Eigen::Vector3d> cropped;
  cropped.reserve(scan.size());
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const double r2 = scan[i].cast<double>().squaredNorm();
    if (r2 < r2min || r2 > r2max || (exclude && (*exclude)[i])) continue;
    cropped.push_back(scan[i].cast<double>());
  }
  OdometryStep step;
  step.first = first;
  if (s_.exclude_road_users) {
    cropped = downsample(cropped, s_.geometry_spacing);
    const auto kinds = splitScanGeometry(cropped, s_.geometry);
    std::size_t n = 0;
    for (std::size_t k = 0; k < cropped.size(); ++k)
      if (kinds[k] != ScanPointKind::kRoadUser) cropped[n++] = cropped[k];
    step.road_user_points = cropped.size() - n;
    cropped.resize(n);
  }
  // The map-resolution frame (first point per voxel), de-skewed with one sweep of the last
  // motion (kiss-icp, eq. (3)), and the registration points.
  std::vector<Eigen::Vector3d> frame = downsample(cropped, s_.scan_spacing);
  if (s_.deskew && velocity_known) {
    std::vector<Eigen::Vector3f> raw(frame.size());
    for (std::size_t k = 0; k < frame.size(); ++k) raw[k] = frame[k].cast<float>();
    frame = deskewScan(raw, scaleMotion(last_delta_, s_.sweep_period / last_dt_));
  }
  const std::vector<Eigen::Vector3d> source = downsample(frame, s_.source_spacing);
  step.points = source.size();
  if (source.size() < static_cast<std::size_t>(s_.registration.min_correspondences))
    throw InputError("odometry: a scan has " + std::to_string(source.size()) +
                     " points after filtering, fewer than " +
                     std::to_string(s_.registration.min_correspondences));

  if (first) {
    step.converged = true;
    step.keyframe = true;
    poses_.push_back(Pose3::Identity());
    steps_.push_back(step);
    insertKeyframe(frame, Pose3::Identity());
    if (s_.deskew) first_frame_ = frame;  // de-skewed once the velocity is known
    return steps_.back();
  }
  // Constant-velocity prediction from the last trusted pose (untrusted ones are predictions
  // themselves); registration with the adaptive threshold (kiss-icp eq. (4)-(5), (9)-(12)), then
  // with the fine one.
  since_trusted_ += dt;
  const Pose3& T_prev = trusted_pose_;
  const Pose3 delta =
      velocity_known ? scaleMotion(last_delta_, since_trusted_ / last_dt_) : Pose3::Identity();
  const Pose3 T_pred = orthonormalized(T_prev * delta);
  const double sig = sigma();
  step.threshold = 3.0 * sig;
  MapRegistrationSettings coarse = s_.registration;  // it only has to land near the fine pass
  coarse.convergence = 10.0 * s_.registration.convergence;
  MapRegistrationResult reg =
      registerToMap(map_, source, T_pred, std::max(step.threshold, s_.fine_threshold), sig, coarse);
  const int coarse_iterations = reg.iterations;  // the fine pass decides convergence
  reg = registerToMap(map_, source, orthonormalized(reg.T_map_scan), s_.fine_threshold,
                      s_.fine_threshold / 3.0, s_.registration);
  reg.T_map_scan = orthonormalized(reg.T_map_scan);
  reg.iterations += coarse_iterations;
  step.converged = reg.converged;
  step.iterations = reg.iterations;
  step.correspondences = reg.correspondences;
  step.inlier_share = reg.inlier_share;
  step.rmse = reg.rmse;
  const double constraint = translationConstraint(map_, source, reg.T_map_scan, s_.fine_threshold);
  step.assessment = assessStep(reg, T_prev, velocity_known ? &T_pred : nullptr, since_trusted_,
                               constraint, s_.trust);
  if (!step.assessment.trusted) {
    poses_.push_back(T_pred);
    steps_.push_back(step);
    return steps_.back();
  }
  const Pose3 T = reg.T_map_scan;
  // Adaptive threshold from the deviation of the prediction (kiss-icp, eq. (4)-(5)).
  const double err = modelError(T_pred.inverse() * T, s_.max_range);
  if (err > s_.min_motion) {
    model_sse_ += err * err;
    ++model_samples_;
  }
  last_delta_ = orthonormalized(T_prev.inverse() * T);
  last_dt_ = since_trusted_;
  if (!first_frame_.empty()) {
    // The first sweep entered the map before any motion was known: now it can be de-skewed.
    std::vector<Eigen::Vector3f> raw(first_frame_.size());
    for (std::size_t k = 0; k < raw.size(); ++k) raw[k] = first_frame_[k].cast<float>();
    map_ = LocalVoxelMap(map_.settings());
    insertKeyframe(deskewScan(raw, scaleMotion(last_delta_, s_.sweep_period / last_dt_)),
                   Pose3::Identity());
    first_frame_.clear();
  }
  const Pose3 since_key = keyframe_.inverse() * T;
  if (since_key.translation().norm() >= s_.keyframe_distance ||
      Eigen::AngleAxisd(since_key.linear()).angle() * 180.0 / M_PI >= s_.keyframe_angle) {
    insertKeyframe(frame, T);
    step.keyframe = true;
  }
  trusted_pose_ = T;
  since_trusted_ = 0.0;
  poses_.push_back(T);
  steps_.push_back(step);
  return steps_.back();
}

}  // namespace mapfuse::lidar
