#include "mapfuse/lidar/drive_odometry.hpp"

#include <chrono>
#include <cmath>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/progress.hpp"
#include "mapfuse/io/velodyne.hpp"

namespace mapfuse::lidar {

double frameInterval(const io::KittiRawFrame& prev, const io::KittiRawFrame& cur,
                     double frame_period) {
  const double dt = cur.timestamp - prev.timestamp;
  if (std::isfinite(dt) && dt > 0) return dt;
  return (cur.index - prev.index) * frame_period;
}

DriveOdometryResult runDriveOdometry(const io::KittiRawDrive& drive,
                                     const DriveOdometrySettings& s) {
  if (s.max_untrusted < 0) throw ConfigError("odometry: max_untrusted must be >= 0");
  if (!(s.frame_period > 0)) throw ConfigError("odometry: frame_period must be > 0");
  const auto t0 = std::chrono::steady_clock::now();
  ScanOdometry odo(s.odometry);
  DriveOdometryResult res;
  int untrusted = 0;
  Progress progress("odometry scans", drive.frames.size());
  for (std::size_t i = 0; i < drive.frames.size(); ++i) {
    const auto& f = drive.frames[i];
    const double dt = i == 0 ? 0.0 : frameInterval(drive.frames[i - 1], f, s.frame_period);
    const OdometryStep& st = odo.add(io::readVelodyneBin(f.velodyne).points, dt);
    res.frame_index.push_back(f.index);
    progress.advance();
    if (st.trusted()) continue;
    ++untrusted;
    MAPFUSE_WARN("odometry: frame " << f.index << " untrusted: " << st.assessment.reasons);
    if (untrusted > s.max_untrusted) {
      progress.finish();
      throw InputError(
          "odometry: frame " + std::to_string(f.index) + " (" + f.velodyne.string() +
          ") is untrusted: " + st.assessment.reasons + "; " + std::to_string(untrusted) +
          " untrusted step(s) exceed odom_max_untrusted = " + std::to_string(s.max_untrusted) +
          ". Nothing was written.");
    }
  }
  progress.finish();
  if (untrusted > 0) {
    std::string frames;
    for (std::size_t i = 0; i < odo.steps().size(); ++i)
      if (!odo.steps()[i].trusted())
        frames += (frames.empty() ? "" : ", ") + std::to_string(drive.frames[i].index);
    MAPFUSE_WARN("odometry: " << untrusted << " untrusted step(s) tolerated (odom_max_untrusted = "
                              << s.max_untrusted << "): frames " << frames);
  }
  res.T_odom_velo = odo.poses();
  res.steps = odo.steps();
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

nlohmann::json odometryReport(const DriveOdometryResult& r, const DriveOdometrySettings& s) {
  using json = nlohmann::json;
  int converged = 0, trusted = 0;
  double length = 0;
  json steps = json::array(), untrusted = json::array();
  for (std::size_t i = 0; i < r.steps.size(); ++i) {
    const OdometryStep& st = r.steps[i];
    if (st.first) continue;
    converged += st.converged;
    trusted += st.trusted();
    length += (r.T_odom_velo[i].translation() - r.T_odom_velo[i - 1].translation()).norm();
    const StepAssessment& a = st.assessment;
    steps.push_back({{"frame", r.frame_index[i]},
                     {"converged", st.converged},
                     {"iterations", st.iterations},
                     {"inlier_share", st.inlier_share},
                     {"rmse", st.rmse},
                     {"threshold", st.threshold},
                     {"points", st.points},
                     {"road_user_points", st.road_user_points},
                     {"speed", a.speed},
                     {"rotation_rate", a.rotation_rate},
                     {"deviation_m", a.deviation_m},
                     {"constraint", a.constraint},
                     {"trusted", st.trusted()}});
    if (!st.trusted()) untrusted.push_back({{"frame", r.frame_index[i]}, {"reasons", a.reasons}});
  }
  const std::size_t n_steps = r.steps.empty() ? 0 : r.steps.size() - 1;
  return {{"steps_total", n_steps},
          {"converged_scans", converged},
          {"trusted_steps", trusted},
          {"untrusted_steps", untrusted},
          {"max_untrusted", s.max_untrusted},
          {"travelled_distance_m", length},
          {"scans_per_second", r.seconds > 0 ? double(r.steps.size()) / r.seconds : 0.0},
          {"steps", steps}};
}

}  // namespace mapfuse::lidar
