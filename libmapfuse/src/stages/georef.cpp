#include "mapfuse/stages/georef.hpp"

#include <chrono>
#include <exception>
#include <sstream>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/stage_report.hpp"

namespace mapfuse::stages {

void GeorefParams::validate() const {
  const char* st = "GeorefParams";
  requireParam(odom_sigma_translation_per_m >= 0, st, "odom_sigma_translation_per_m",
               odom_sigma_translation_per_m, ">= 0");
  requireParam(odom_sigma_rotation_per_m >= 0, st, "odom_sigma_rotation_per_m",
               odom_sigma_rotation_per_m, ">= 0");
  requireParam(odom_min_sigma_translation > 0, st, "odom_min_sigma_translation",
               odom_min_sigma_translation, "> 0");
  requireParam(odom_min_sigma_rotation > 0, st, "odom_min_sigma_rotation", odom_min_sigma_rotation,
               "> 0");
  requireParam(gravity_sigma >= 0, st, "gravity_sigma", gravity_sigma, ">= 0");
  requireParam(gps_max_extrapolation >= 0, st, "gps_max_extrapolation", gps_max_extrapolation,
               ">= 0");
  requireParam(cauchy_scale > 0, st, "cauchy_scale", cauchy_scale, "> 0");
  requireParam(chi2_gate > 0, st, "chi2_gate", chi2_gate, "> 0");
  requireParam(max_rejection_rounds >= 1, st, "max_rejection_rounds", max_rejection_rounds, ">= 1");
  requireParam(max_iterations >= 1, st, "max_iterations", max_iterations, ">= 1");
  requireParam(threads >= 1, st, "threads", threads, ">= 1");
  if (!origin.empty()) parseOrigin(origin);
}

fusion::GeorefSettings GeorefParams::settings() const {
  fusion::GeorefSettings s;
  s.odom_sigma_translation_per_m = odom_sigma_translation_per_m;
  s.odom_sigma_rotation_per_m = odom_sigma_rotation_per_m;
  s.odom_min_sigma_translation = odom_min_sigma_translation;
  s.odom_min_sigma_rotation = odom_min_sigma_rotation;
  s.gravity_sigma = gravity_sigma;
  s.gps_time_offset = gps_time_offset;
  s.gps_max_extrapolation = gps_max_extrapolation;
  s.cauchy_scale = cauchy_scale;
  s.chi2_gate = chi2_gate;
  s.max_rejection_rounds = max_rejection_rounds;
  s.max_iterations = max_iterations;
  return s;
}

geo::GeoOrigin parseOrigin(const std::string& text) {
  std::istringstream is(text);
  geo::GeoOrigin o;
  char c1 = 0, c2 = 0;
  if (!(is >> o.lat >> c1 >> o.lon >> c2 >> o.alt) || c1 != ',' || c2 != ',' ||
      !(is >> std::ws).eof() || !geo::isValid(o))
    throw ConfigError("GeorefParams::origin = \"" + text +
                      "\". Violated constraint: lat,lon,alt with lat in [-90, 90], lon in "
                      "[-180, 180]");
  return o;
}

nlohmann::json runGeoref(const std::vector<std::string>& inputs,
                         const std::filesystem::path& out_dir, const GeorefParams& params) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  params.validate();
  if (inputs.empty()) throw InputError("georef: no input LSM");
  std::vector<Lsm> lsms;
  for (const auto& in : inputs) lsms.push_back(io::readLsm(in));
  for (std::size_t i = 0; i < inputs.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (std::filesystem::path(inputs[i]).filename() ==
          std::filesystem::path(inputs[j]).filename())
        throw InputError("georef: inputs " + inputs[j] + " and " + inputs[i] +
                         " share a file name (outputs would collide)");

  geo::GeoOrigin origin;
  std::string origin_source = "config";
  if (!params.origin.empty()) {
    origin = parseOrigin(params.origin);
  } else {
    if (lsms[0].gps.empty()) throw InputError(inputs[0] + ": no GPS fix to derive the origin from");
    origin = lsms[0].gps[0].position;
    origin_source = "first GPS fix of " + inputs[0];
  }

  const fusion::GeorefSettings settings = params.settings();
  const int n = int(lsms.size());
  std::vector<fusion::GeorefResult> results(n);
  std::vector<double> seconds(n);
  std::vector<std::exception_ptr> errors(n);
  // One thread per input at most: a per-drive batch job (one LSM) must not start and spin an
  // idle OpenMP worker (it doubled the CPU time of such jobs).
#pragma omp parallel for schedule(dynamic) num_threads(std::max(1, std::min(params.threads, n)))
  for (int i = 0; i < n; ++i) {
    try {
      const auto t = Clock::now();
      results[i] = fusion::georeferenceLsm(lsms[i], origin, settings, inputs[i]);
      seconds[i] = std::chrono::duration<double>(Clock::now() - t).count();
    } catch (...) {
      errors[i] = std::current_exception();
    }
  }
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);

  std::filesystem::create_directories(out_dir);
  nlohmann::json per = nlohmann::json::array();
  int rejected = 0;
  for (int i = 0; i < n; ++i) {
    const auto& r = results[i];
    io::writeLsm(out_dir / std::filesystem::path(inputs[i]).filename(), r.lsm);
    rejected += r.gps_rejected;
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
                   {"seconds", seconds[i]}});
    MAPFUSE_INFO("georef: " << inputs[i] << ": " << r.gps_used << " GPS fixes used, "
                            << r.gps_rejected << " rejected, residual rms " << r.residual_rms
                            << " m");
  }
  nlohmann::json summary = {
      {"origin", {{"lat", origin.lat}, {"lon", origin.lon}, {"alt", origin.alt}}},
      {"origin_source", origin_source},
      {"lsms", per},
      {"gps_rejected_total", rejected},
      {"converged",
       std::all_of(results.begin(), results.end(), [](const auto& r) { return r.converged; })},
      {"seconds", std::chrono::duration<double>(Clock::now() - t0).count()}};
  io::writeResolvedConfig(out_dir, "georef", paramsToJson(params));
  io::writeSummary(out_dir, "georef", summary);
  return summary;
}

}  // namespace mapfuse::stages
