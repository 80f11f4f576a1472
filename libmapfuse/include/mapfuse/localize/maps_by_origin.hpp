#pragma once
/// @file The map in each drive's ENU frame, built once per origin (docs/localize.md): its match
/// index, and with a truth map the map's own frame against the truth (estimateMapToTruth).
/// Drives that share an origin share both.
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/localize/localizer.hpp"
#include "mapfuse/localize/map_frame.hpp"
#include "mapfuse/localize/map_index.hpp"

namespace mapfuse::localize {

/// The map as one drive sees it.
struct MapInDriveFrame {
  std::shared_ptr<const MapIndex> index;   ///< the map in the drive's ENU
  std::optional<MapToTruth> map_to_truth;  ///< with a truth map: map -> truth in that ENU
};

class MapsByOrigin {
 public:
  /// `map` and `truth_map` (optional) in their own origins; `settings` gives match_attributes and
  /// the matching of estimateMapToTruth.
  MapsByOrigin(const VectorMap& map, const std::optional<VectorMap>& truth_map,
               const LocalizeSettings& settings);

  /// @brief The map in `origin`'s ENU: the one of the first earlier origin that is the same
  /// (geo::sameOrigin), else built now. @throws InputError from estimateMapToTruth.
  MapInDriveFrame at(const geo::GeoOrigin& origin);

 private:
  const VectorMap& map_;
  const std::optional<VectorMap>& truth_map_;
  const LocalizeSettings& settings_;
  std::vector<std::pair<geo::GeoOrigin, MapInDriveFrame>> seen_;  ///< one per distinct origin
};

}  // namespace mapfuse::localize
