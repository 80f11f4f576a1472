#include "mapfuse/stages/update.hpp"

#include <map>

#include "map_writers.hpp"
#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/parallel_for.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/map_changes_io.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/vector_map_io.hpp"
#include "mapfuse/update/map_apply.hpp"

namespace mapfuse::stages {

namespace {

// Per stretch of a new drive its registration to the map (docs/update.md).
nlohmann::json stretchesToJson(const std::vector<update::StretchOffset>& stretches,
                               const std::vector<std::string>& inputs) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& o : stretches)
    j.push_back({{"drive", inputs.empty() ? std::string() : inputs[o.drive]},
                 {"from_m", o.from},
                 {"to_m", o.to},
                 {"registered", o.registered},
                 {"offset_enu_m", {o.t.x(), o.t.y(), o.t.z()}},
                 {"yaw_rad", o.yaw},
                 {"inliers", o.inliers},
                 {"rmse_m", o.rmse}});
  return j;
}

// The updated map in aggregate's formats (map_writers.hpp; map.cbor at full precision, not
// compact); map.osm's lanelets take their travel directions from the new drives (registered),
// the only drives update reads.
void writeUpdatedMap(const std::filesystem::path& out_dir, const VectorMap& map,
                     const std::vector<Lsm>& drives, io::Lanelet2ExportStats* osm_stats) {
  const lanelet::LaneletSettings lanelet;
  const auto writers = vectorMapWriters(out_dir, map, drives, lanelet, {}, osm_stats);
  parallelFor(writers.size(), [&](std::size_t i) { writers[i](); });
}

nlohmann::json toJson(const update::UpdatedMap& m, std::size_t before,
                      const io::Lanelet2ExportStats& osm) {
  return {{"instances_before", before},
          {"instances_after", m.map.instances.size()},
          {"unchanged", m.unchanged.size()},
          {"changed_ids", m.changed},
          {"removed_ids", m.removed},
          {"added_ids", m.added},
          {"lanelets", osm.lanelets},
          {"lanelets_direction_known", osm.lanelets_direction_known}};
}

}  // namespace

nlohmann::json toJson(const update::UpdateResult& result, const std::vector<std::string>& inputs) {
  std::map<std::string, int> by_kind;
  for (int k = 0; k < kNumChangeKinds; ++k) by_kind[changeKindName(ChangeKind(k))] = 0;
  for (const auto& c : result.changes.changes) ++by_kind[changeKindName(c.kind)];
  const auto& s = result.stats;
  return {{"traversals", s.traversals},
          {"observations_used", s.observations_used},
          {"changes", result.changes.changes.size()},
          {"changes_by_kind", by_kind},
          {"elements_in_view", s.elements_in_view},
          {"confirmed", s.confirmed},
          {"undecided", s.undecided},
          {"not_verified", s.not_verified.size()},
          {"not_verified_ids", s.not_verified},
          {"stretch_offsets", stretchesToJson(s.stretches, inputs)}};
}

update::UpdateResult runUpdate(const std::filesystem::path& map_path,
                               const std::vector<std::string>& inputs,
                               const std::filesystem::path& out_dir, const UpdateParams& params) {
  validateParams(params);
  if (inputs.empty()) throw InputError("no new drive (LSM) given");
  io::OutputTransaction outputs(out_dir);  // locked and writable before the work
  const VectorMap map = io::readVectorMap(map_path);
  const std::vector<Lsm> lsms = io::readLsmInputs(inputs, /*covariances=*/false);
  update::UpdateResult result = update::detectChanges(map, lsms, inputs, params.detection);
  MAPFUSE_INFO("update: " << result.changes.changes.size() << " changes, "
                          << result.stats.not_verified.size() << " of " << map.instances.size()
                          << " map elements not verified (no new drive had them in view)");
  const update::UpdatedMap updated = update::applyChanges(map, result.changes);
  io::Lanelet2ExportStats osm;
  writeUpdatedMap(out_dir, updated.map, result.registered, &osm);
  io::writeMapChanges(out_dir / "changes.json", result.changes);
  io::writeMapChangesGeoJson(out_dir / "changes.geojson", result.changes);
  // The new drives in the map's frame, whole (covariances re-read): for a rebuild with them.
  io::writeWithKeyframes(inputs, result.registered, out_dir / "registered");
  io::writeResolvedConfig(out_dir, "update", paramsToJson(params));
  nlohmann::json summary = toJson(result, inputs);
  summary["updated_map"] = toJson(updated, map.instances.size(), osm);
  io::writeSummary(out_dir, "update", summary);
  outputs.commit();
  return result;
}

}  // namespace mapfuse::stages
