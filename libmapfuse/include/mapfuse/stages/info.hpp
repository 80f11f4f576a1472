#pragma once
/// @file Stage `info`: what a mapfuse file holds (format, counts, frame, origin, extent), and
/// the shared ENU origin that per-drive georef jobs of one batch must agree on.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "mapfuse/geo/origin.hpp"

namespace mapfuse::stages {

/// `info` has no parameters; --config accepts an empty object.
struct InfoParams {
  static constexpr const char* kName = "InfoParams";
  template <class V>
  void visit(V&) {}
};

/// What an LSM holds.
struct LsmInfo {
  std::string drive_id, vehicle_id;
  std::string frame;  ///< "enu" or "odom"
  std::size_t keyframes = 0, gps_fixes = 0, elements = 0;
  std::map<std::string, int> elements_per_class;  ///< by class name, classes present only
  double trajectory_length_m = 0;                 ///< along the keyframe positions
  std::optional<double> duration_s;               ///< first to last keyframe stamp
  std::optional<geo::GeoOrigin> origin;           ///< when georeferenced
};

/// What a vector map holds.
struct MapInfo {
  std::string source;
  geo::GeoOrigin origin;
  std::size_t instances = 0;
  std::map<std::string, int> instances_per_class;  ///< by class name, classes present only
  double lane_line_length_m = 0;
};

/// What a mapfuse file holds: the facts of its format.
struct FileInfo {
  std::string file, format;
  std::uintmax_t bytes = 0;
  std::optional<LsmInfo> lsm;  ///< format mapfuse.lsm
  std::optional<MapInfo> map;  ///< format mapfuse.vector_map
  std::size_t tiles = 0;       ///< format mapfuse.tiles
  std::string stage;           ///< format mapfuse.summary
};

/// @brief One JSON object: file, format, bytes and the facts of the format.
nlohmann::json toJson(const FileInfo& info);

/// @brief Facts about an LSM, vector map, tiles manifest or summary file.
/// @throws IoError, ParseError (malformed file or unknown format).
FileInfo describeFile(const std::filesystem::path& path);

/// @brief The ENU origin a file implies for a batch: an LSM's own origin when georeferenced,
/// else its first GPS fix; a vector map's origin (new drives of a map update share the map's).
/// @throws InputError when an LSM has neither, ParseError for other documents.
geo::GeoOrigin originOf(const std::filesystem::path& path);

}  // namespace mapfuse::stages
