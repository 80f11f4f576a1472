#pragma once
/// @file Stage `georef` (§4.1, eq. (4)-(6), Song et al. 2023): reads LSMs, georeferences each in
/// ENU of one origin shared by the whole run (fusion::georeferenceLsms), writes them, the
/// resolved config and georef.summary.json.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mapfuse/fusion/georef.hpp"

namespace mapfuse::stages {

/// @brief True when `text` is "lat,lon,alt" of a valid WGS84 point.
bool isOriginText(const std::string& text);

struct GeorefParams {
  static constexpr const char* kName = "GeorefParams";
  std::string origin;  ///< "lat,lon,alt"; empty = first GPS fix of the first LSM
  fusion::GeorefSettings georef;
  int threads = 2;  ///< OpenMP threads over LSMs

  template <class V>
  void visit(V& v) {
    v("origin", origin, "deg,deg,m", "shared ENU origin lat,lon,alt (empty: first GPS fix)",
      param::TextRule{[](const std::string& t) { return t.empty() || isOriginText(t); },
                      "empty or lat,lon,alt with lat in [-90, 90], lon in [-180, 180]"});
    georef.visit(v);
    v("threads", threads, "", "OpenMP threads over LSMs", param::in(1, 1024));
  }
};

/// @brief Parses "lat,lon,alt". @throws ConfigError naming the value.
geo::GeoOrigin parseOrigin(const std::string& text);

/// What one georef run did: the shared origin and each LSM's result, in input order.
struct GeorefRun {
  geo::GeoOrigin origin;
  std::string origin_source;  ///< "config" or "first GPS fix of <file>"
  std::vector<fusion::GeorefResult> lsms;
};

/// @brief The summary georef.summary.json holds.
nlohmann::json toJson(const GeorefRun& run, const std::vector<std::string>& inputs);

/// @brief Georeferences every input LSM; writes <out_dir>/<same file name> for each (atomically,
/// only after all succeeded), georef.config.json and georef.summary.json.
/// @throws IoError, ParseError, InputError (exit 3) for unusable inputs.
GeorefRun runGeoref(const std::vector<std::string>& inputs, const std::filesystem::path& out_dir,
                    const GeorefParams& params);

}  // namespace mapfuse::stages
