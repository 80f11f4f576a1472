#pragma once
/// @file Subcommands of `evaluate`. Each command file (map_command.cpp, voxels_command.cpp, ...)
/// registers itself with a static MAPFUSE_EVALUATE_COMMAND so main.cpp needs no list.
#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mapfuse/cli/app.hpp"

namespace mapfuse::apps {

/// What a subcommand's setup returns: the action to run when that subcommand was chosen.
using CommandAction = std::function<void()>;

struct Command {
  std::string name;  ///< e.g. "map", "voxels"
  std::string help;  ///< one line for --help
  /// Adds the subcommand's options to `sub` and returns its action.
  std::function<CommandAction(CLI::App& sub)> setup;
};

/// What a subcommand that runs a stage binds its options to: the stage's parameters and inputs
/// and the -o/--out folder. Shared by the setup and the action it returns.
template <class Params, class Inputs>
struct StageCommandState {
  Params params;
  Inputs inputs;
  std::string out_dir;
};

/// @brief The end of a stage subcommand's setup: adds -o/--out (`out_help`) and one option per
/// parameter, and returns the action, which reads --config into the parameters, checks them and
/// calls `run(*state)`.
template <class State, class Run>
CommandAction stageCommand(CLI::App& sub, std::shared_ptr<State> state, const char* out_help,
                           Run run) {
  sub.add_option("-o,--out", state->out_dir, out_help)->required();
  cli::addParamOptions(sub, state->params);
  return [state, &sub, run] {
    cli::applyCommandConfig(sub, state->params);
    run(*state);
  };
}

/// @brief Adds a command to the registry (called from static initializers).
bool registerCommand(Command command);
/// @brief All registered commands, sorted by name.
std::vector<Command>& registeredCommands();

}  // namespace mapfuse::apps

#define MAPFUSE_EVALUATE_COMMAND(var, ...) \
  static const bool var = ::mapfuse::apps::registerCommand(::mapfuse::apps::Command{__VA_ARGS__})
