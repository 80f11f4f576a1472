// Stage configuration files (configs/<stage>.json, --config): the document reader and each
// of the 13 stages' strict parameter reading (cli/params.hpp: unknown keys, nulls, wrong types,
// integers that do not fit, values outside a declared rule) and validation, exactly as a tool reads
// --config (paramsFromFile on a file). The first byte chooses the stage, the rest is the file.
// Every refusal must be a configuration error (exit 2), an empty or truncated file included.
// Accepted parameters are written as the tool's <stage>.config.json and read back equal.
#include "fuzz_support.hpp"
#include "mapfuse/cli/params.hpp"
#include "mapfuse/stages/aggregate.hpp"
#include "mapfuse/stages/align.hpp"
#include "mapfuse/stages/balance.hpp"
#include "mapfuse/stages/evaluate_map.hpp"
#include "mapfuse/stages/evaluate_voxels.hpp"
#include "mapfuse/stages/georef.hpp"
#include "mapfuse/stages/info.hpp"
#include "mapfuse/stages/lidar_semantic_map.hpp"
#include "mapfuse/stages/lsm_build.hpp"
#include "mapfuse/stages/simulate.hpp"
#include "mapfuse/stages/simulate_lidar.hpp"
#include "mapfuse/stages/tile.hpp"
#include "mapfuse/tiling/stitch.hpp"

using namespace mapfuse;

namespace {

template <class Params>
void apply(const std::filesystem::path& file) {
  Params params;
  if (!fuzz::accepts(
          [&] {
            paramsFromFile(params, file.string());
            validateParams(params);
          },
          {ExitCode::kUsage}))
    return;
  // What the stage writes as <stage>.config.json reads back to the same parameters.
  const nlohmann::json written = paramsToJson(params);
  Params again;
  paramsFromJson(again, written, "again.config.json");
  validateParams(again);
  MAPFUSE_FUZZ_CHECK(paramsToJson(again) == written);
}

using Apply = void (*)(const std::filesystem::path&);
const Apply kStages[] = {apply<stages::AggregateParams>,
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
                         apply<tiling::StitchParams>,
                         apply<stages::InfoParams>};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto file = fuzz::scratchDir() / "fuzz.config.json";
  fuzz::writeFile(file, fuzz::bytesOf(data + 1, size - 1));
  kStages[data[0] % (sizeof kStages / sizeof kStages[0])](file);
  return 0;
}
