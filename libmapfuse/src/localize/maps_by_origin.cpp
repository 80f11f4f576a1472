#include "mapfuse/localize/maps_by_origin.hpp"

#include "mapfuse/eval/map_metrics.hpp"

namespace mapfuse::localize {

MapsByOrigin::MapsByOrigin(const VectorMap& map, const std::optional<VectorMap>& truth_map,
                           const LocalizeSettings& settings)
    : map_(map), truth_map_(truth_map), settings_(settings) {}

MapInDriveFrame MapsByOrigin::at(const geo::GeoOrigin& origin) {
  for (const auto& [o, m] : seen_)
    if (geo::sameOrigin(o, origin)) return m;  // built for an earlier drive of this origin
  MapInDriveFrame m;
  const VectorMap map = eval::inOrigin(map_, origin);
  m.index = std::make_shared<MapIndex>(map, settings_.match_attributes);
  if (truth_map_)
    m.map_to_truth = estimateMapToTruth(
        map, MapIndex(eval::inOrigin(*truth_map_, origin), settings_.match_attributes), settings_);
  seen_.emplace_back(origin, m);
  return m;
}

}  // namespace mapfuse::localize
