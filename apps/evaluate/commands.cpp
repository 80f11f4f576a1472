#include "commands.hpp"

#include <algorithm>

namespace mapfuse::apps {

std::vector<Command>& registeredCommands() {
  static std::vector<Command> commands;
  return commands;
}

bool registerCommand(Command command) {
  auto& all = registeredCommands();
  all.push_back(std::move(command));
  std::sort(all.begin(), all.end(),
            [](const Command& a, const Command& b) { return a.name < b.name; });
  return true;
}

}  // namespace mapfuse::apps
