/// @file evaluate: scores mapfuse products against ground truth. One subcommand per registered
/// command file (map_command.cpp: `evaluate map`, voxels_command.cpp: `evaluate voxels`, ...);
/// each gets --config, -v and --quiet. docs/evaluate.md.
#include "commands.hpp"
#include "mapfuse/cli/app.hpp"

static const char* const kAbout =
    "Evaluate mapfuse products against ground truth; choose one subcommand.\n"
    "Exit codes: 0 ok, 2 usage/config, 3 bad input, 4 I/O.";

int main(int argc, char** argv) {
  mapfuse::cli::CommandTool tool("evaluate", kAbout);
  for (const auto& c : mapfuse::apps::registeredCommands()) tool.add(c.name, c.help, c.setup);
  return tool.run(argc, argv);
}
