#include "mapfuse/cli/app.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>

#include "mapfuse/cli/output_guard.hpp"
#include "version.hpp"

namespace mapfuse::cli {

void addCommonOptions(CLI::App& app, CommonOptions& common) {
  app.add_option("--config", common.config_file,
                 "JSON file mirroring the parameters (configs/<stage>.json); command-line "
                 "options override it")
      ->check(CLI::ExistingFile);
  app.add_flag("-v,--verbose", common.verbosity, "More log output on stderr (repeatable)");
  app.add_flag("-q,--quiet", common.quiet, "No progress or info lines, warnings and errors only");
}

void applyCommonOptions(const CommonOptions& common) {
  if (common.quiet)
    setLogLevel(LogLevel::kWarn);
  else if (common.verbosity > 0)
    setLogLevel(LogLevel::kDebug);
  else
    setLogLevel(LogLevel::kInfo);
}

std::string optionHelp(const char* help, const char* unit, const std::string& rule) {
  std::string text = help;
  if (unit && *unit) text += " [" + std::string(unit) + "]";
  if (!rule.empty()) text += " (" + rule + ")";
  return text;
}

namespace detail {
std::string CliVisitor::listDefault(const std::vector<double>& values) {
  std::string text;
  for (std::size_t i = 0; i < values.size(); ++i)
    text += (i ? "," : "") + param::showNumber(values[i]);
  return text;
}
}  // namespace detail

std::string optionName(const char* key) {
  std::string name = std::string("--") + key;
  for (char& c : name)
    if (c == '_') c = '-';
  return name;
}

namespace {
std::exception_ptr g_deferred;
}  // namespace

void deferError(std::exception_ptr error) {
  if (!g_deferred) g_deferred = error;
}

int run(CLI::App& app, int argc, char** argv, const std::function<void()>& body) {
  const std::string tool = app.get_name();
  try {
    if (g_deferred) {
      const std::exception_ptr e = g_deferred;
      g_deferred = nullptr;
      std::rethrow_exception(e);
    }
    if (!app.get_option_no_throw("--version"))
      app.set_version_flag("--version", versionText(), "Print the mapfuse version and exit");
    try {
      app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
      return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
      return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
      return app.exit(e);
    } catch (const CLI::ParseError& e) {
      // CLI11's own errors (missing argument, unknown option) in the one-line form of every
      // other error.
      std::cerr << tool << ": error: " << e.what() << " (see " << tool << " --help)\n";
      return static_cast<int>(ExitCode::kUsage);
    }
    checkOutputsOfCommandLine(app);  // before any work: -o never overlaps an input
    body();
    return static_cast<int>(ExitCode::kOk);
  } catch (const Error& e) {
    std::cerr << tool << ": error: " << e.what() << '\n';
    return static_cast<int>(e.exitCode());
  } catch (const std::filesystem::filesystem_error& e) {
    // A file-system call no reader wrapped (a name too long, a permission denied): still an
    // I/O error naming the path, not an internal one.
    std::cerr << tool << ": error: " << e.what() << '\n';
    return static_cast<int>(ExitCode::kIo);
  } catch (const std::bad_alloc&) {
    std::cerr << tool << ": error: out of memory\n";
    return static_cast<int>(ExitCode::kInternal);
  } catch (const std::exception& e) {
    std::cerr << tool << ": internal error: " << e.what() << '\n';
    return static_cast<int>(ExitCode::kInternal);
  }
}

CommandTool::CommandTool(const char* name, const char* description) : app_(description, name) {
  app_.require_subcommand(1);
}

void CommandTool::add(const std::string& name, const std::string& help, const Setup& setup) {
  Command c;
  c.sub = app_.add_subcommand(name, help);
  c.common = std::make_unique<CommonOptions>();
  addCommonOptions(*c.sub, *c.common);
  c.action = setup(*c.sub);
  commands_.push_back(std::move(c));
}

int CommandTool::run(int argc, char** argv) {
  return cli::run(app_, argc, argv, [&] {
    for (const auto& c : commands_)
      if (c.sub->parsed()) {
        applyCommonOptions(*c.common);
        c.action();
      }
  });
}

void printLine(const std::string& line) {
  std::cout << line << '\n';
}

std::vector<std::string> expandInputList(const std::vector<std::string>& args) {
  std::vector<std::string> out;
  auto readList = [&](std::istream& in) {
    std::string line;
    while (std::getline(in, line)) {
      const auto b = line.find_first_not_of(" \t\r");
      if (b == std::string::npos || line[b] == '#') continue;
      const auto e = line.find_last_not_of(" \t\r");
      out.push_back(line.substr(b, e - b + 1));
    }
  };
  for (const auto& a : args) {
    if (a == "-") {
      readList(std::cin);
    } else if (!a.empty() && a[0] == '@') {
      std::ifstream in(a.substr(1));
      if (!in) throw IoError(a.substr(1), "cannot open input list");
      readList(in);
    } else {
      out.push_back(a);
    }
  }
  return out;
}

std::string configArgument(int argc, char** argv) {
  std::string file;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--config" && i + 1 < argc)
      file = argv[i + 1];
    else if (arg.rfind("--config=", 0) == 0)
      file = arg.substr(9);
  }
  return file;
}

}  // namespace mapfuse::cli
