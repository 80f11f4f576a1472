#include "mapfuse/stages/lsm_build_pipeline.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <map>

#include "mapfuse/vehicle/body_tilt.hpp"
#include "mapfuse/vehicle/dead_reckoning.hpp"
#include "mapfuse/vehicle/ground_ranging.hpp"
#include "mapfuse/vehicle/lsm_assembly.hpp"
#include "mapfuse/vehicle/triangulation.hpp"
#include "mapfuse/vehicle/vanishing_point.hpp"

namespace mapfuse::stages {
namespace {

using Clock = std::chrono::steady_clock;
/// m, lane observations whose lateral offsets differ less belong to one line (lanes are ~3.5 m
/// apart, a dashed line's dashes share one offset).
constexpr double kLaneGroupGap = 0.8;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

/// Key points of an aerial observation: given points, else derived from the box.
std::vector<Eigen::Vector2d> keyPoints(const vehicle::AerialObservation& a) {
  if (!a.points.empty()) return a.points;
  const Eigen::Vector4d& b = a.box;
  if (a.cls == CrowdClass::kTrafficSign)
    return {Eigen::Vector2d(0.5 * (b(0) + b(2)), 0.5 * (b(1) + b(3)))};
  return {Eigen::Vector2d(0.5 * (b(0) + b(2)), b(3)), Eigen::Vector2d(0.5 * (b(0) + b(2)), b(1))};
}

}  // namespace

ProcessedDrive processDrive(const LoadedDrive& d, const LsmBuildParams& p) {
  ProcessedDrive out;
  const std::size_t n = d.frames.size();
  const Eigen::Matrix3d K_inv = d.calib.K.inverse();
  const auto t_all = Clock::now();

  // 1. Ground plane per frame: tilted with the body (body_tilt.hpp), then calibrated from lane
  // vanishing points (§3.2.1) against that plane.
  auto t = Clock::now();
  out.planes.resize(n, d.calib.ground);
  if (p.tilt_window > 0) {
    const auto tilt = vehicle::roadTiltInBody(d.T_odom_body, d.stamps, p.tilt_window);
    for (std::size_t i = 0; i < n; ++i)
      out.planes[i].normal_cam = vehicle::tiltByBodyRotation(d.calib.ground.normal_cam, tilt[i],
                                                             d.calib.T_body_cam.linear());
  }
  out.pitch_corrections.assign(n, 0.0);
  if (p.vp_calibration) {
    vehicle::VanishingSettings vs;
    vs.max_line_rms = p.vp_max_line_rms;
    vs.max_pitch_correction = p.max_pitch_correction;
    vs.window = p.vp_window;
    std::vector<std::optional<double>> per_frame(n);
#pragma omp parallel for schedule(dynamic)
    for (int i = 0; i < int(n); ++i) {
      // Lane pixels in the fitting band, grouped by their lateral offset on the nominal plane
      // so that the dashes of one dashed line are fitted as one line.
      std::vector<std::pair<double, std::vector<Eigen::Vector2d>>> obs;
      for (const auto& g : d.frames[i].ground) {
        if (g.cls != CrowdClass::kLaneLine) continue;
        std::vector<Eigen::Vector2d> near;
        std::vector<double> lateral;
        for (const auto& px : g.pixels) {
          const auto X = vehicle::backProjectToGround(px, K_inv, d.calib.ground);
          if (!X || X->norm() < p.min_range || X->norm() > p.vp_max_range) continue;
          near.push_back(px);
          lateral.push_back(X->x() * std::max(0.2, 15.0 / X->norm()));  // shrink far distortion
        }
        if (near.empty()) continue;
        std::nth_element(lateral.begin(), lateral.begin() + lateral.size() / 2, lateral.end());
        obs.push_back({lateral[lateral.size() / 2], std::move(near)});
      }
      std::sort(obs.begin(), obs.end(),
                [](const auto& a, const auto& b) { return a.first < b.first; });
      std::vector<std::vector<Eigen::Vector2d>> lanes;
      for (std::size_t k = 0; k < obs.size(); ++k) {
        if (k == 0 || obs[k].first - obs[k - 1].first > kLaneGroupGap) lanes.emplace_back();
        lanes.back().insert(lanes.back().end(), obs[k].second.begin(), obs[k].second.end());
      }
      per_frame[i] = vehicle::estimatePitchCorrection(lanes, d.calib.K, out.planes[i], vs);
    }
    for (const auto& c : per_frame) out.vp_frames += c ? 1 : 0;
    out.pitch_corrections = vehicle::smoothCorrections(per_frame, p.vp_window);
  }
  for (std::size_t i = 0; i < n; ++i)
    out.planes[i].normal_cam =
        vehicle::tiltNormal(out.planes[i].normal_cam, out.pitch_corrections[i], 0.0);
  const double t_calib = since(t);

  // 2. Ground ranging (eq. 1) into the odom frame, frame-parallel.
  t = Clock::now();
  vehicle::RangingSettings rs;
  rs.min_range = p.min_range;
  rs.max_range = p.max_range;
  rs.sigma_pixel = p.sigma_pixel;
  rs.sigma_height = p.sigma_height;
  rs.sigma_pitch = rs.sigma_roll = p.sigma_attitude;
  std::vector<std::vector<vehicle::RangedMarking>> per_frame(n);
#pragma omp parallel for schedule(dynamic)
  for (int i = 0; i < int(n); ++i) {
    const Pose3 T_odom_cam = d.T_odom_body[i] * d.calib.T_body_cam;
    for (const auto& g : d.frames[i].ground) {
      vehicle::RangedMarking m;
      m.cls = g.cls;
      m.attributes = g.attributes;
      m.track_id = g.track_id;
      m.truth_id = g.truth_id;
      m.frame = i;
      for (const auto& gp : vehicle::rangeGroundPolyline(g.pixels, d.calib.K, out.planes[i], rs)) {
        m.points.push_back(T_odom_cam * gp.p_cam);
        m.covariances.push_back(rotateCovariance(T_odom_cam.linear(), gp.cov_cam));
      }
      const std::size_t need = geometryKind(g.cls) == GeometryKind::kPlanar ? 1 : 2;
      if (m.points.size() >= need) per_frame[i].push_back(std::move(m));
    }
  }
  std::vector<vehicle::RangedMarking> markings;
  for (auto& f : per_frame)
    for (auto& m : f) markings.push_back(std::move(m));
  const double t_ranging = since(t);

  // 3. Aerial triangulation (eq. 2-3), track-parallel.
  t = Clock::now();
  struct Track {
    CrowdClass cls;
    std::vector<std::pair<int, const vehicle::AerialObservation*>> obs;
  };
  std::map<std::pair<int, int64_t>, Track> tracks;
  int unassociated = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (const auto& a : d.frames[i].aerial) {
      if (a.track_id < 0) {
        ++unassociated;
        continue;
      }
      auto& tr = tracks[{int(a.cls), a.track_id}];
      tr.cls = a.cls;
      tr.obs.push_back({int(i), &a});
    }
  std::vector<const Track*> track_list;
  for (const auto& [k, tr] : tracks) track_list.push_back(&tr);
  std::vector<std::optional<vehicle::AerialElement>> elements(track_list.size());
  std::vector<std::string> reasons(track_list.size());
  vehicle::TriangulationSettings ts;
  ts.min_parallax = p.min_parallax;
  ts.min_observations = p.min_track_frames;
  ts.sigma_pixel = p.track_sigma_pixel;
  ts.huber_delta = p.huber_delta;
  ts.max_reprojection_rms = p.max_reprojection_rms;
  ts.max_range = p.max_track_range;
#pragma omp parallel for schedule(dynamic)
  for (int k = 0; k < int(track_list.size()); ++k) {
    const Track& tr = *track_list[k];
    std::size_t nkp = 1000;
    for (const auto& [i, a] : tr.obs) nkp = std::min(nkp, keyPoints(*a).size());
    vehicle::AerialElement el;
    el.cls = tr.cls;
    el.observations = int(tr.obs.size());
    std::map<int64_t, int> votes;
    for (const auto& [i, a] : tr.obs) ++votes[a->truth_id];
    int best = 0;
    for (const auto& [id, c] : votes)
      if (c > best) best = c, el.truth_id = id;
    bool ok = nkp > 0 && nkp < 1000;
    std::vector<Eigen::Vector3d> pts;
    for (std::size_t kp = 0; ok && kp < nkp; ++kp) {
      std::vector<vehicle::TrackObservation> obs;
      for (const auto& [i, a] : tr.obs)
        obs.push_back({d.T_odom_body[i] * d.calib.T_body_cam, keyPoints(*a)[kp]});
      const auto r = vehicle::triangulateTrack(d.calib.K, obs, ts);
      if (!r.ok) {
        reasons[k] = r.reason;
        ok = false;
        break;
      }
      pts.push_back(r.p_world);
      el.covariances.push_back(r.covariance);
    }
    if (!ok) continue;
    if (tr.cls == CrowdClass::kTrafficSign) {
      el.points = pts;
    } else {
      el.points = {pts[0]};
      el.covariances.resize(1);
      el.height = pts.size() > 1 ? std::max(0.0, pts[1].z() - pts[0].z()) : 0.0;
    }
    elements[k] = el;
  }
  std::vector<vehicle::AerialElement> aerial;
  std::map<std::string, int> rejected;
  for (std::size_t k = 0; k < elements.size(); ++k) {
    if (elements[k])
      aerial.push_back(*elements[k]);
    else
      ++rejected[reasons[k].empty() ? "keypoints" : reasons[k]];
  }
  const double t_tri = since(t);

  // 4. Keyframes and assembly (§3.3).
  t = Clock::now();
  const auto kf = vehicle::selectKeyframes(d.T_odom_body, p.keyframe_spacing, p.keyframe_max_angle);
  vehicle::AssemblySettings as;
  as.association_radius = p.association_radius;
  as.point_spacing = p.point_spacing;
  as.max_element_length = p.max_element_length;
  as.min_observations = p.min_observations;
  as.keyframe_sigma_translation = p.keyframe_sigma_translation;
  as.keyframe_sigma_rotation = p.keyframe_sigma_rotation;
  vehicle::AssemblyStats ast;
  out.lsm = vehicle::assembleLsm(d.T_odom_body, d.stamps, kf, markings, aerial, as, &ast);
  out.lsm.drive_id = d.drive_id;
  out.lsm.vehicle_id = d.vehicle_id;
  out.lsm.frame = LsmFrame::kOdom;
  out.lsm.gps = d.gps;
  const double t_assembly = since(t);

  double mean_corr = 0.0;
  for (double c : out.pitch_corrections) mean_corr += c / double(std::max<std::size_t>(1, n));
  out.stats = {{"frames", n},
               {"keyframes", kf.size()},
               {"vp_frames", out.vp_frames},
               {"mean_pitch_correction_rad", mean_corr},
               {"ranged_markings", markings.size()},
               {"ground_instances", ast.ground_instances},
               {"ground_instances_dropped", ast.ground_dropped},
               {"aerial_tracks", track_list.size()},
               {"aerial_triangulated", aerial.size()},
               {"aerial_rejected", rejected},
               {"aerial_unassociated_observations", unassociated},
               {"elements", out.lsm.elements.size()},
               {"gps_fixes", out.lsm.gps.size()},
               {"seconds",
                {{"calibration", t_calib},
                 {"ranging", t_ranging},
                 {"triangulation", t_tri},
                 {"assembly", t_assembly},
                 {"total", since(t_all)}}}};
  return out;
}

}  // namespace mapfuse::stages
