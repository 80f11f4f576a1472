#include "mapfuse/vehicle/lsm_build.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <optional>

#include "aerial_tracks.hpp"
#include "body_tilt.hpp"
#include "mapfuse/core/pose_at_stamp.hpp"
#include "mapfuse/geo/origin.hpp"
#include "path_surface.hpp"

namespace mapfuse::vehicle {
namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}
}  // namespace

void calibrateGroundPlanes(const DriveData& d, const LsmBuildSettings& s, LsmBuildResult& out) {
  const std::size_t n = d.frames.size();
  // The nominal plane tilted with the body (body_tilt.hpp).
  out.planes.assign(n, d.calib.ground);
  out.tilt = BodyTiltStats{};
  if (s.tilt_window > 0) {
    const auto tilt =
        roadTiltInBody(d.T_odom_body, d.stamps, s.tilt_window,
                       s.tilt_weighting == "hann" ? TiltWeighting::kHann : TiltWeighting::kBox,
                       s.ranging.path_surface ? sharpVerticalCurves(d.T_odom_body, s.ranging)
                                              : std::vector<bool>{});
    BodyTiltStats& st = out.tilt;
    st.source = "ego-motion";
    st.weighting = s.tilt_weighting;
    st.window = s.tilt_window;
    st.moves_height = s.tilt_moves_height;
    st.frames = int(n);
    for (std::size_t i = 0; i < n; ++i) {
      out.planes[i].normal_cam =
          tiltByBodyRotation(d.calib.ground.normal_cam, tilt[i], d.calib.T_body_cam.linear());
      if (s.tilt_moves_height)
        out.planes[i].height = tiltedCameraHeight(d.calib.ground.height, d.calib.ground.normal_cam,
                                                  tilt[i], d.calib.T_body_cam);
      const Eigen::Vector3d w = Eigen::Vector3d::UnitZ().cross(tilt[i].col(2));  // small angles
      st.roll_rms += w.x() * w.x();
      st.pitch_rms += w.y() * w.y();
      st.roll_max = std::max(st.roll_max, std::abs(w.x()));
      st.pitch_max = std::max(st.pitch_max, std::abs(w.y()));
      const double dh = out.planes[i].height - d.calib.ground.height;
      st.height_change_rms += dh * dh;
    }
    const double m = double(std::max<std::size_t>(1, n));
    st.roll_rms = std::sqrt(st.roll_rms / m);
    st.pitch_rms = std::sqrt(st.pitch_rms / m);
    st.height_change_rms = std::sqrt(st.height_change_rms / m);
  }
  // Lane vanishing points against that plane (§3.2.1), only where the ego-motion shows a straight
  // road ahead and the VP lies on the motion's direction; pooled, or the static extrinsic kept
  // (vp_gate.hpp).
  out.pitch_corrections.assign(n, 0.0);
  out.vp = VpCalibration{};
  if (s.vanishing.enabled) {
    const Eigen::Matrix3d K_inv = d.calib.K.inverse();
    std::vector<std::optional<VanishingEstimate>> per_frame(n);
    std::vector<Eigen::Vector3d> normals(n);
#pragma omp parallel for schedule(dynamic)
    for (int i = 0; i < int(n); ++i) {
      const auto lanes = laneLinePixels(d.frames[i], K_inv, d.calib.ground, s.ranging.min_range,
                                        s.vanishing.max_range);
      per_frame[i] = estimateVanishing(lanes, d.calib.K, out.planes[i], s.vanishing);
      normals[i] = out.planes[i].normal_cam;
    }
    const auto motion = lookAheadMotion(d.T_odom_body, s.vanishing.max_range);
    out.vp = gateVanishingPoints(per_frame, motion, normals,
                                 d.calib.T_body_cam.linear().transpose(), s.vanishing);
    out.vp_frames = out.vp.accepted;
    out.pitch_corrections = out.vp.corrections;
  }
  for (std::size_t i = 0; i < n; ++i)
    out.planes[i].normal_cam = tiltNormal(out.planes[i].normal_cam, out.pitch_corrections[i], 0.0);
}

std::vector<RangedMarking> rangeMarkings(const DriveData& d, const std::vector<GroundPlane>& planes,
                                         const RangingSettings& s, int* points, int* on_path_out) {
  const std::size_t n = d.frames.size();
  std::optional<PathSurface> path;  // the road ahead, only when ranged on (path_surface)
  if (s.path_surface) path.emplace(d.T_odom_body, d.calib.T_body_cam, planes, s);
  std::vector<std::vector<RangedMarking>> per_frame(n);
  std::vector<int> ranged(n, 0), on_path(n, 0);
#pragma omp parallel for schedule(dynamic)
  for (int i = 0; i < int(n); ++i) {
    const Pose3 T_odom_cam = d.T_odom_body[i] * d.calib.T_body_cam;
    for (const auto& g : d.frames[i].ground) {
      RangedMarking m;
      m.cls = g.cls;
      m.attributes = g.attributes;
      m.track_id = g.track_id;
      m.truth_id = g.truth_id;
      m.frame = i;
      for (const auto& px : g.pixels) {
        bool ahead = false;
        // eq. (1): on the road ahead (path_surface.hpp), or on the plane under the camera
        const auto gp = path ? path->range(i, px, d.calib.K, s, &ahead)
                             : rangeGroundPixel(px, d.calib.K, planes[i], s);
        if (!gp) continue;
        ++ranged[i];
        on_path[i] += ahead ? 1 : 0;
        m.points.push_back(T_odom_cam * gp->p_cam);
        m.covariances.push_back(rotateCovariance(T_odom_cam.linear(), gp->cov_cam));
      }
      const std::size_t need = geometryKind(g.cls) == GeometryKind::kPlanar ? 1 : 2;
      if (m.points.size() >= need) per_frame[i].push_back(std::move(m));
    }
  }
  if (points) *points = std::accumulate(ranged.begin(), ranged.end(), 0);
  if (on_path_out) *on_path_out = std::accumulate(on_path.begin(), on_path.end(), 0);
  std::vector<RangedMarking> markings;
  for (auto& f : per_frame)
    for (auto& m : f) markings.push_back(std::move(m));
  return markings;
}

geo::TrackAgreement egoMotionAgainstGps(const DriveData& d) {
  std::vector<Eigen::Vector3d> odom, enu;
  if (d.gps.empty() || d.stamps.size() < 2) return {};
  const geo::EnuConverter conv(d.gps.front().position);
  for (const GpsFix& f : d.gps) {
    const auto T = poseAtStamp(
        d.stamps.size(), f.stamp, [&](std::size_t i) { return d.stamps[i]; },
        [&](std::size_t i) { return d.T_odom_body[i]; });
    if (!T) continue;  // a fix outside the frames' time span
    odom.push_back(T->translation());
    enu.push_back(conv.toEnu(f.position));
  }
  return geo::trackAgreement(odom, enu, geo::kScaleWindow);
}

LsmBuildResult buildLsm(const DriveData& d, const LsmBuildSettings& s) {
  LsmBuildResult out;
  const std::size_t n = d.frames.size();
  const auto t_all = Clock::now();

  // 1. Ground plane per frame (§3.2.1).
  auto t = Clock::now();
  calibrateGroundPlanes(d, s, out);
  out.seconds_calibration = since(t);

  // 2. Ground ranging (eq. 1) into the odom frame, frame-parallel.
  t = Clock::now();
  const std::vector<RangedMarking> markings =
      rangeMarkings(d, out.planes, s.ranging, &out.ranged_points, &out.ranged_on_path);
  out.seconds_ranging = since(t);

  // 3. Aerial triangulation (eq. 2-3), track-parallel.
  t = Clock::now();
  AerialTracks aerial = triangulateAerialTracks(d, s.triangulation);
  out.seconds_triangulation = since(t);

  // 4. Keyframes and assembly (§3.3).
  t = Clock::now();
  const auto kf = selectKeyframes(d.T_odom_body, s.keyframes.spacing, s.keyframes.max_angle);
  out.lsm = assembleLsm(d.T_odom_body, d.stamps, kf, markings, aerial.elements, s.assembly,
                        &out.assembly);
  out.lsm.drive_id = d.drive_id;
  out.lsm.vehicle_id = d.vehicle_id;
  out.lsm.frame = LsmFrame::kOdom;
  out.lsm.gps = d.gps;
  out.seconds_assembly = since(t);

  for (double c : out.pitch_corrections)
    out.mean_pitch_correction += c / double(std::max<std::size_t>(1, n));
  out.gps_agreement = egoMotionAgainstGps(d);
  out.frames = int(n);
  out.keyframes = int(kf.size());
  out.ranged_markings = int(markings.size());
  out.aerial_tracks = aerial.tracks;
  out.aerial_triangulated = int(aerial.elements.size());
  out.aerial_rejected = std::move(aerial.rejected);
  out.aerial_unassociated_observations = aerial.unassociated;
  out.seconds_total = since(t_all);
  return out;
}

}  // namespace mapfuse::vehicle
