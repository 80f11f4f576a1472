/// @file update: an existing vector map + new drives' LSMs -> change report (docs/update.md).
/// Prints the summary's change counts as JSON on stdout.

#include "about.hpp"
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/update.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  cli::StageTool<stages::UpdateParams> tool("update", apps::about::kUpdate);
  const auto& map = tool.existingFile("--map", "the existing vector map (mapfuse.vector_map)");
  const auto& lsms = tool.inputs("lsms", cli::kLsmListHelp);
  const auto& out = tool.out("Output folder");
  return tool.run(argc, argv, [&](const stages::UpdateParams& params) {
    const auto j = stages::toJson(stages::runUpdate(map, lsms, out, params), lsms);
    return nlohmann::json{{"changes_by_kind", j["changes_by_kind"]},
                          {"not_verified", j["not_verified"]}}
        .dump();
  });
}
