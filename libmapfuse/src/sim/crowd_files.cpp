#include "mapfuse/sim/crowd_files.hpp"

#include <nlohmann/json.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/progress.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/json_geometry.hpp"
#include "mapfuse/io/lsm_io.hpp"

namespace mapfuse::sim {
namespace {

/// The true trajectory of a drive at the given samples (mapfuse.trajectory).
nlohmann::json trajectoryJson(const Drive& d, const std::vector<std::size_t>& samples,
                              const geo::GeoOrigin& origin) {
  nlohmann::json j;
  j["format"] = "mapfuse.trajectory";
  j["version"] = 1;
  j["drive_id"] = d.drive_id;
  j["vehicle_id"] = d.vehicle_id;
  j["frame"] = "enu";
  j["origin"] = io::originToJson(origin);
  j["sensor_errors"] = {{"wheel_scale_error", d.wheel_scale_error},
                        {"gyro_bias", {d.gyro_bias.x(), d.gyro_bias.y(), d.gyro_bias.z()}},
                        {"gps_initial_bias_enu", {d.gps_bias0.x(), d.gps_bias0.y()}}};
  nlohmann::json poses = nlohmann::json::array();
  for (std::size_t i = 0; i < samples.size(); ++i)
    poses.push_back({{"id", static_cast<int64_t>(i)},
                     {"stamp", d.stamps[samples[i]]},
                     {"pose", io::poseToJson(d.truth[samples[i]])}});
  j["poses"] = poses;
  return j;
}

}  // namespace

CrowdStats writeCrowdTraversals(const Crowd& crowd, const CrowdSettings& settings,
                                const CrowdFiles& files, const geo::GeoOrigin& origin,
                                const std::filesystem::path& out) {
  const int n = settings.traversals;
  const std::string ext = files.format == "cbor" ? ".lsm.cbor" : ".lsm.json";
  std::vector<CrowdStats> stats(n);
  std::vector<std::string> errors(n);
  Progress progress("simulate", n);
#pragma omp parallel for schedule(dynamic)
  for (int i = 0; i < n; ++i) {
    try {
      const Traversal t = crowd.traversal(i, &stats[i]);
      const std::string& id = t.drive.drive_id;
      // True poses at the LSM keyframes, or at every camera frame (frames: evaluate matches).
      const auto samples = files.level == "frames" ? cameraSamples(t.drive, settings.drive)
                                                   : t.observed.keyframe_samples;
      io::writeDocument(out / "truth" / (id + ".trajectory.json"),
                        trajectoryJson(t.drive, samples, origin));
      if (files.level == "lsm") io::writeLsm(out / "lsm" / (id + ext), t.observed.lsm);
      if (files.level == "frames") stats[i].frames = crowd.writeFrames(t, out / "frames" / id);
    } catch (const std::exception& e) {
      errors[i] = e.what();
    }
#pragma omp critical(simulate_progress)
    progress.advance();
  }
  progress.finish();
  for (const auto& e : errors)
    if (!e.empty()) throw Error("simulate: " + e);
  CrowdStats total;
  for (const auto& s : stats) total.add(s);
  return total;
}

}  // namespace mapfuse::sim
