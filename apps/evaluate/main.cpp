/// @file evaluate: scores mapfuse products against ground truth. One subcommand per registered
/// command file (map_command.cpp: `evaluate map`, voxels_command.cpp: `evaluate voxels`, ...);
/// each gets --config, -v and --quiet. docs/evaluate.md.
#include "about.hpp"
#include "commands.hpp"
#include "mapfuse/cli/app.hpp"

int main(int argc, char** argv) {
  mapfuse::cli::CommandTool tool("evaluate", mapfuse::apps::about::kEvaluate);
  for (const auto& c : mapfuse::apps::registeredCommands()) tool.add(c.name, c.help, c.setup);
  return tool.run(argc, argv);
}
