#include "mapfuse/stages/georef.hpp"

#include <algorithm>
#include <chrono>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/stage_report.hpp"

namespace mapfuse::stages {

bool isOriginText(const std::string& text) {
  return geo::parseLatLonAlt(text).has_value();
}

geo::GeoOrigin parseOrigin(const std::string& text) {
  if (const auto o = geo::parseLatLonAlt(text)) return *o;
  throw ConfigError("GeorefParams::origin = \"" + text +
                    "\". Violated constraint: lat,lon,alt with lat in [-90, 90], lon in "
                    "[-180, 180]");
}

nlohmann::json toJson(const GeorefRun& run, const std::vector<std::string>& inputs) {
  nlohmann::json per = nlohmann::json::array();
  int rejected = 0;
  nlohmann::json untrusted = nlohmann::json::array();
  for (std::size_t i = 0; i < run.lsms.size(); ++i) {
    const auto& r = run.lsms[i];
    rejected += r.gps_rejected;
    if (!r.trusted) untrusted.push_back(r.lsm.drive_id);
    per.push_back({{"input", inputs[i]},
                   {"drive_id", r.lsm.drive_id},
                   {"keyframes", r.lsm.keyframes.size()},
                   {"converged", r.converged},
                   {"iterations", r.iterations},
                   {"final_cost", r.final_cost},
                   {"gps_total", r.gps_total},
                   {"gps_used", r.gps_used},
                   {"gps_rejected", r.gps_rejected},
                   {"gps_dropped", r.gps_dropped},
                   {"rejected_stamps", r.rejected_stamps},
                   {"residual_mean_m", r.residual_mean},
                   {"residual_rms_m", r.residual_rms},
                   {"residual_max_m", r.residual_max},
                   {"residual_h_rms_m", r.residual_h_rms},
                   {"residual_v_rms_m", r.residual_v_rms},
                   {"residual_v_mean_m", r.residual_v_mean},
                   {"odom_vertical_slope", r.odom_vertical_slope},
                   {"odom_scale_error", r.odom_scale_error},
                   {"trusted", r.trusted},
                   {"seconds", r.seconds}});
  }
  return {{"origin", {{"lat", run.origin.lat}, {"lon", run.origin.lon}, {"alt", run.origin.alt}}},
          {"origin_source", run.origin_source},
          {"lsms", per},
          {"gps_rejected_total", rejected},
          {"untrusted_drives", untrusted},
          {"converged", std::all_of(run.lsms.begin(), run.lsms.end(),
                                    [](const auto& r) { return r.converged; })}};
}

GeorefRun runGeoref(const std::vector<std::string>& inputs, const std::filesystem::path& out_dir,
                    const GeorefParams& params) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  validateParams(params);
  io::OutputTransaction outputs(out_dir);  // locked and writable before the work
  if (inputs.empty()) throw InputError("georef: no input LSM");
  const std::vector<Lsm> lsms = io::readLsmInputs(inputs);
  for (std::size_t i = 0; i < inputs.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (std::filesystem::path(inputs[i]).filename() ==
          std::filesystem::path(inputs[j]).filename())
        throw InputError("georef: inputs " + inputs[j] + " and " + inputs[i] +
                         " share a file name (outputs would collide)");

  GeorefRun run;
  run.origin_source = "config";
  if (!params.origin.empty()) {
    run.origin = parseOrigin(params.origin);
  } else {
    if (lsms[0].gps.empty()) throw InputError(inputs[0] + ": no GPS fix to derive the origin from");
    run.origin = lsms[0].gps[0].position;
    run.origin_source = "first GPS fix of " + inputs[0];
  }
  run.lsms = fusion::georeferenceLsms(lsms, run.origin, params.georef, inputs, params.threads);

  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const auto& r = run.lsms[i];
    io::writeLsm(out_dir / std::filesystem::path(inputs[i]).filename(), r.lsm);
    MAPFUSE_INFO("georef: " << inputs[i] << ": " << r.gps_used << " GPS fixes used, "
                            << r.gps_rejected << " rejected, residual rms " << r.residual_rms
                            << " m");
    if (!r.trusted)
      MAPFUSE_WARN("georef: " << inputs[i] << ": drive " << r.lsm.drive_id
                              << " untrusted: odometry and GPS disagree, " << r.gps_rejected
                              << " of " << r.gps_rejected + r.gps_used
                              << " fixes rejected, residual rms horizontal " << r.residual_h_rms
                              << " m, vertical " << r.residual_v_rms << " m, odometry height slope "
                              << r.odom_vertical_slope << ", scale error " << r.odom_scale_error
                              << " (bounds: trust_* in docs/fusion.md)");
  }
  nlohmann::json summary = toJson(run, inputs);
  summary["seconds"] = std::chrono::duration<double>(Clock::now() - t0).count();
  io::writeResolvedConfig(out_dir, "georef", paramsToJson(params));
  io::writeSummary(out_dir, "georef", summary);
  outputs.commit();
  return run;
}

}  // namespace mapfuse::stages
