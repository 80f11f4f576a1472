#pragma once
/// @file Subcommands of `evaluate`. Each command file (map_command.cpp, voxels_command.cpp, ...)
/// registers itself with a static MAPFUSE_EVALUATE_COMMAND so main.cpp needs no list.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace mapfuse::apps {

/// What a subcommand's setup returns: the action to run when that subcommand was chosen.
using CommandAction = std::function<void()>;

struct Command {
  std::string name;  ///< e.g. "map", "voxels"
  std::string help;  ///< one line for --help
  /// Adds the subcommand's options to `sub` and returns its action.
  std::function<CommandAction(CLI::App& sub)> setup;
};

/// @brief Adds a command to the registry (called from static initializers).
bool registerCommand(Command command);
/// @brief All registered commands, sorted by name.
std::vector<Command>& registeredCommands();

}  // namespace mapfuse::apps

#define MAPFUSE_EVALUATE_COMMAND(var, ...) \
  static const bool var = ::mapfuse::apps::registerCommand(::mapfuse::apps::Command{__VA_ARGS__})
