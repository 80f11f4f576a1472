// Issue 21, step 1: where the frames-level lane wiggle comes from. On simulated frames drives
// (truth/poses.csv known) this compares, per frame, the ground plane lsm-build ranges with
// (calibrateGroundPlanes: ego-motion tilt over tilt_window, VP gate) against the true plane of
// the road under the camera, and the lateral error of ranged lane points that plane error
// causes (the same pixel ranged on the used and on the true plane, eq. 1; pixel noise is thus
// left out). The plane error is split into
//   - pitch / roll of the normal (body frame), itself split into what the window leaves of the
//     true suspension motion (the same tilt computed from the TRUE poses) and what the
//     dead-reckoned attitude adds (gyro noise and bias);
//   - camera height (the camera sits ahead of the body's pivot, so a pitching body moves it up
//     and down; the tilt keeps the nominal height).
// Prints Markdown tables: RMS lateral error per lateral band for the plane as used and with each
// part replaced by its true value, RMS attitude / height errors, and per-frame correlations.
// usage: bench_attitude_error --drive DIR [--drive DIR ...] [--tilt-window S] [--vp 0|1]
#include <CLI/CLI.hpp>
#include <Eigen/Geometry>
#include <cmath>
#include <iostream>

#include "mapfuse/core/log.hpp"
#include "mapfuse/io/drive_frames.hpp"
#include "mapfuse/vehicle/dead_reckoning.hpp"
#include "mapfuse/vehicle/ground_ranging.hpp"
#include "mapfuse/vehicle/lsm_build.hpp"

using namespace mapfuse;

namespace {
constexpr int kBands = 4;           // lateral bands of 3 m
constexpr double kBandWidth = 3.0;  // m

struct Accum {
  double sum2[kBands] = {0, 0, 0, 0};
  long n[kBands] = {0, 0, 0, 0};
  void add(double lateral_m, double err) {
    const int b = int(std::abs(lateral_m) / kBandWidth);
    if (b < 0 || b >= kBands) return;
    sum2[b] += err * err;
    ++n[b];
  }
  std::string row() const {
    std::string s;
    char buf[32];
    for (int b = 0; b < kBands; ++b) {
      std::snprintf(buf, sizeof buf, " %.3f |", n[b] ? std::sqrt(sum2[b] / n[b]) : 0.0);
      s += buf;
    }
    return s;
  }
};

double corr(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = double(a.size());
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i] / n, mb += b[i] / n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : 0.0;
}

double rms(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return v.empty() ? 0.0 : std::sqrt(s / double(v.size()));
}

/// Small rotation taking unit vector a to b, in the body frame: (roll = x, pitch = y).
Eigen::Vector2d tiltBetween(const Eigen::Vector3d& a_body, const Eigen::Vector3d& b_body) {
  const Eigen::Vector3d w = a_body.cross(b_body);
  return {w.x(), w.y()};
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app("lsm-build ground-plane error against the simulator's truth",
               "bench_attitude_error");
  std::vector<std::string> drives;
  double tilt_window = -1.0;
  int vp = -1, moves_height = -1;
  std::string weighting;
  app.add_option("--drive", drives, "simulated frames drive folder(s)")->required();
  app.add_option("--tilt-window", tilt_window, "s (default: lsm-build's)");
  app.add_option("--vp", vp, "vp_calibration 0/1 (default: lsm-build's)");
  app.add_option("--tilt-weighting", weighting, "box | hann (default: lsm-build's)");
  app.add_option("--tilt-moves-height", moves_height, "0/1 (default: lsm-build's)");
  CLI11_PARSE(app, argc, argv);
  setLogLevel(LogLevel::kWarn);

  vehicle::LsmBuildSettings s;
  if (tilt_window >= 0) s.tilt_window = tilt_window;
  if (vp >= 0) s.vanishing.enabled = vp == 1;
  if (!weighting.empty()) s.tilt_weighting = weighting;
  if (moves_height >= 0) s.tilt_moves_height = moves_height == 1;

  // Lateral error of ranged lane points per band, with the plane: as used; true normal (height
  // as used); true height (normal as used); normal from the window over the TRUE poses (what
  // the window leaves of the suspension motion, no gyro error) with the true height.
  Accum used, true_normal, true_height, window_only, lever;
  Accum others;  // stop lines, arrows, crosswalks; bands of forward distance / 2.5
  std::vector<double> pitch_err_ends, pitch_err_inner;
  std::vector<double> pitch_err, roll_err, height_err, pitch_win, roll_win, pitch_true,
      frame_lat_far, frame_scale_pred, lever_err;
  for (const auto& dir : drives) {
    const io::DriveFrames df = io::readDriveFrames(dir);
    if (df.truth_T_enu_body.size() != df.frames.size()) {
      std::cerr << dir << ": no truth poses\n";
      return 3;
    }
    vehicle::DriveData d;
    d.calib = df.calib;
    d.frames = df.observations;
    for (const auto& f : df.frames) d.stamps.push_back(f.stamp);
    d.T_odom_body = vehicle::deadReckon(df.imu, df.wheel, d.stamps, {});
    vehicle::LsmBuildResult res;
    vehicle::calibrateGroundPlanes(d, s, res);
    // The same window over the true poses (relative to the first), no VP.
    vehicle::DriveData dt = d;
    const Pose3 T0inv = df.truth_T_enu_body.front().inverse();
    for (std::size_t i = 0; i < d.stamps.size(); ++i)
      dt.T_odom_body[i] = T0inv * df.truth_T_enu_body[i];
    vehicle::LsmBuildSettings st = s;
    st.vanishing.enabled = false;
    vehicle::LsmBuildResult rest;
    vehicle::calibrateGroundPlanes(dt, st, rest);

    const Eigen::Matrix3d R_body_cam = d.calib.T_body_cam.linear();
    const Eigen::Vector3d t_body_cam = d.calib.T_body_cam.translation();
    vehicle::RangingSettings rs = s.ranging;
    for (std::size_t i = 0; i < d.frames.size(); ++i) {
      // True plane: level road (z up in ENU) through the body origin's height.
      const Pose3& T_enu_body = df.truth_T_enu_body[i];
      const Pose3 T_enu_cam = T_enu_body * d.calib.T_body_cam;
      GroundPlane truth;
      truth.normal_cam = T_enu_cam.linear().transpose() * Eigen::Vector3d::UnitZ();
      truth.height = T_enu_cam.translation().z() - T_enu_body.translation().z();
      const GroundPlane& est = res.planes[i];
      const Eigen::Vector2d e =
          tiltBetween(R_body_cam * truth.normal_cam, R_body_cam * est.normal_cam);
      const Eigen::Vector2d w =
          tiltBetween(R_body_cam * truth.normal_cam, R_body_cam * rest.planes[i].normal_cam);
      const Eigen::Vector2d tp =
          tiltBetween(Eigen::Vector3d::UnitZ(), R_body_cam * truth.normal_cam);
      roll_err.push_back(e.x());
      pitch_err.push_back(e.y());
      // Frames whose window is cut by the drive's start or end.
      const double half = 0.5 * s.tilt_window;
      if (d.stamps[i] - d.stamps.front() < half || d.stamps.back() - d.stamps[i] < half)
        pitch_err_ends.push_back(e.y());
      else
        pitch_err_inner.push_back(e.y());
      roll_win.push_back(w.x());
      pitch_win.push_back(w.y());
      pitch_true.push_back(tp.y());
      height_err.push_back(est.height - truth.height);
      GroundPlane tn = truth, th = truth, wo = truth;
      tn.height = est.height;
      th.normal_cam = est.normal_cam;
      wo.normal_cam = rest.planes[i].normal_cam;
      // The plane as used, its height moved with the tilt as if the body pivoted about its origin
      // (height = h0 + (n_body - e_z) . t_body_cam).
      GroundPlane lv = est;
      lv.height = d.calib.ground.height +
                  (R_body_cam * est.normal_cam - Eigen::Vector3d::UnitZ()).dot(t_body_cam);
      lever_err.push_back(lv.height - truth.height);
      double lat_sum = 0, scale_sum = 0;
      int lat_n = 0;
      for (const auto& g : d.frames[i].ground) {
        if (g.cls != CrowdClass::kLaneLine) {
          // Stop lines, arrows, crosswalks: horizontal error per band of forward distance.
          const Eigen::Matrix3d K_inv = d.calib.K.inverse();
          for (const auto& px : g.pixels) {
            const auto X = vehicle::rangeGroundPixel(px, d.calib.K, truth, rs);
            const auto Y = vehicle::backProjectToGround(px, K_inv, est);
            if (!X || !Y) continue;
            const Eigen::Vector3d a = R_body_cam * X->p_cam, b = R_body_cam * *Y;
            others.add(a.x() / 2.5, (b - a).head<2>().norm());
          }
          continue;
        }
        for (const auto& px : g.pixels) {
          const auto X = vehicle::rangeGroundPixel(px, d.calib.K, truth, rs);
          if (!X) continue;
          const Eigen::Vector3d Xb = R_body_cam * X->p_cam + t_body_cam;
          auto lateral = [&](const GroundPlane& p) -> std::optional<double> {
            const Eigen::Matrix3d K_inv = d.calib.K.inverse();
            const auto Y = vehicle::backProjectToGround(px, K_inv, p);
            if (!Y) return std::nullopt;
            return (R_body_cam * *Y + t_body_cam).y() - Xb.y();
          };
          if (auto v = lateral(est)) {
            used.add(Xb.y(), *v);
            if (std::abs(Xb.y()) > 3.0) {
              lat_sum += *v / Xb.y();  // relative lateral scale error
              ++lat_n;
            }
          }
          if (auto v = lateral(tn)) true_normal.add(Xb.y(), *v);
          if (auto v = lateral(th)) true_height.add(Xb.y(), *v);
          if (auto v = lateral(wo)) window_only.add(Xb.y(), *v);
          if (auto v = lateral(lv)) lever.add(Xb.y(), *v);
          (void)scale_sum;
        }
      }
      frame_lat_far.push_back(lat_n ? lat_sum / lat_n : 0.0);
      frame_scale_pred.push_back((est.height - truth.height) / truth.height);
    }
  }
  std::cout << "| plane used for ranging | lateral RMS 0-3 m | 3-6 m | 6-9 m | 9-12 m |\n"
            << "|---|---|---|---|---|\n"
            << "| lsm-build's (tilt_window " << s.tilt_window << " s " << s.tilt_weighting
            << ", height " << (s.tilt_moves_height ? "tilted" : "fixed") << ", vp "
            << (s.vanishing.enabled ? "on" : "off") << ") |" << used.row() << "\n"
            << "| true normal, lsm-build's height |" << true_normal.row() << "\n"
            << "| lsm-build's normal, true height |" << true_height.row() << "\n"
            << "| window over the true poses (no gyro error), true height |" << window_only.row()
            << "\n"
            << "| lsm-build's normal, height moved with it (pivot at the body origin) |"
            << lever.row() << "\n\n"
            << "| other ground markings, horizontal RMS at 0-7.5 m ahead | 7.5-15 m | 15-22.5 m | "
               "22.5-30 m |\n|---|---|---|---|\n|"
            << others.row() << "\n\n";
  std::cout << "| per-frame quantity (" << pitch_err.size() << " frames) | RMS |\n|---|---|\n"
            << "| true body pitch against the road [rad] | " << rms(pitch_true) << " |\n"
            << "| pitch error of the normal used [rad] | " << rms(pitch_err) << " |\n"
            << "| ... frames whose window is whole / cut by the drive's ends ("
            << pitch_err_ends.size() << " frames) [rad] | " << rms(pitch_err_inner) << " / "
            << rms(pitch_err_ends) << " |\n"
            << "| roll error of the normal used [rad] | " << rms(roll_err) << " |\n"
            << "| pitch error, window over true poses [rad] | " << rms(pitch_win) << " |\n"
            << "| roll error, window over true poses [rad] | " << rms(roll_win) << " |\n"
            << "| camera height error [m] | " << rms(height_err) << " |\n"
            << "| camera height error, height moved with the normal [m] | " << rms(lever_err)
            << " |\n\n";
  std::cout << "correlation over frames of the mean relative lateral error (|y| > 3 m) with: "
            << "height error / height " << corr(frame_lat_far, frame_scale_pred) << ", pitch error "
            << corr(frame_lat_far, pitch_err) << ", roll error " << corr(frame_lat_far, roll_err)
            << ", true pitch " << corr(frame_lat_far, pitch_true) << "\n";
  return 0;
}
