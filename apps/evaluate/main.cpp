/// @file evaluate: scores mapfuse products against ground truth. One subcommand per registered
/// command file (map_command.cpp: `evaluate map`, voxels_command.cpp: `evaluate voxels`, ...);
/// each gets --config, -v and --quiet. docs/evaluate.md.
#include <vector>

#include "commands.hpp"
#include "mapfuse/cli/app.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  CLI::App app{
      "Evaluate mapfuse products against ground truth; choose one subcommand.\n"
      "Exit codes: 0 ok, 2 usage/config, 3 bad input, 4 I/O.",
      "evaluate"};
  app.require_subcommand(1);
  const auto& commands = apps::registeredCommands();
  std::vector<cli::CommonOptions> common(commands.size());  // sized once: options bind to it
  std::vector<apps::CommandAction> actions(commands.size());
  std::vector<CLI::App*> subs(commands.size());
  for (std::size_t i = 0; i < commands.size(); ++i) {
    subs[i] = app.add_subcommand(commands[i].name, commands[i].help);
    cli::addCommonOptions(*subs[i], common[i]);
    actions[i] = commands[i].setup(*subs[i]);
  }
  return cli::run(app, argc, argv, [&] {
    for (std::size_t i = 0; i < subs.size(); ++i)
      if (subs[i]->parsed()) {
        cli::applyCommonOptions(common[i]);
        actions[i]();
      }
  });
}
