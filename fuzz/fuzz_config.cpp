// Stage configuration files (configs/<stage>.json, --config): the document reader and each
// stage's strict parameter parsing and validation. The first byte chooses the stage, the rest is
// the JSON text. Configuration errors are exit 2; a file that is not JSON is still exit 3 today
// (issue 19 moves it to 2 with the parameter redesign), so both are clean refusals here.
#include <functional>

#include "fuzz_support.hpp"
#include "mapfuse/core/params.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/stages/aggregate.hpp"
#include "mapfuse/stages/align.hpp"
#include "mapfuse/stages/balance.hpp"
#include "mapfuse/stages/evaluate_map.hpp"
#include "mapfuse/stages/evaluate_voxels.hpp"
#include "mapfuse/stages/georef.hpp"
#include "mapfuse/stages/lidar_semantic_map.hpp"
#include "mapfuse/stages/lsm_build.hpp"
#include "mapfuse/stages/simulate.hpp"
#include "mapfuse/stages/simulate_lidar.hpp"
#include "mapfuse/stages/tile.hpp"
#include "mapfuse/tiling/stitch.hpp"

using namespace mapfuse;

namespace {

template <class Params>
void apply(const io::Json& doc) {
  Params params;
  paramsFromJson(params, doc, "fuzz.config.json");
  params.validate();
  paramsToJson(params);  // what the stage writes as <stage>.config.json
}

const std::function<void(const io::Json&)> kStages[] = {apply<stages::AggregateParams>,
                                                        apply<stages::AlignParams>,
                                                        apply<stages::BalanceParams>,
                                                        apply<stages::EvaluateMapParams>,
                                                        apply<stages::EvaluateVoxelsParams>,
                                                        apply<stages::GeorefParams>,
                                                        apply<stages::LidarSemanticMapParams>,
                                                        apply<stages::LsmBuildParams>,
                                                        apply<stages::SimulateParams>,
                                                        apply<stages::SimulateLidarParams>,
                                                        apply<stages::TileParams>,
                                                        apply<tiling::StitchParams>};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto& stage = kStages[data[0] % (sizeof kStages / sizeof kStages[0])];
  const std::string text = fuzz::bytesOf(data + 1, size - 1);
  fuzz::accepts([&] { stage(io::parseDocument(text, io::Encoding::kJson, "fuzz.config.json")); },
                {ExitCode::kUsage, ExitCode::kBadInput});
  return 0;
}
