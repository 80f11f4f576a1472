#pragma once
/// @file Command-line conventions shared by every tool (docs/cli.md): --config FILE,
/// one --option per Params field with its default and unit in --help, -v / --quiet, and
/// the mapping of errors to exit codes (0 ok, 1 internal, 2 usage/config, 3 bad input, 4 I/O).
#include <CLI/CLI.hpp>
#include <exception>
#include <functional>
#include <string>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/params.hpp"
#include "mapfuse/io/document.hpp"

namespace mapfuse::cli {

struct CommonOptions {
  std::string config_file;  ///< --config: JSON mirroring the stage's Params
  int verbosity = 0;        ///< -v (repeatable)
  bool quiet = false;       ///< --quiet: no progress, warnings only
};

/// @brief Adds --config, -v and --quiet.
void addCommonOptions(CLI::App& app, CommonOptions& common);

/// @brief Applies -v / --quiet to the log level.
void applyCommonOptions(const CommonOptions& common);

/// @brief "max_iterations" -> "--max-iterations".
std::string optionName(const char* key);

namespace detail {
struct CliVisitor {
  CLI::App& app;
  const char* group;
  template <class T>
  void operator()(const char* key, T& value, const char* unit, const char* help) {
    std::string text = help;
    if (unit && *unit) text += " [" + std::string(unit) + "]";
    app.add_option(optionName(key), value, text)->capture_default_str()->group(group);
  }
  void operator()(const char* key, bool& value, const char* unit, const char* help) {
    app.add_option(optionName(key), value, help)->capture_default_str()->group(group);
  }
};
}  // namespace detail

/// @brief One option per Params field, in the "Parameters" group of --help.
template <class Params>
void addParamOptions(CLI::App& app, Params& params, const char* group = "Parameters") {
  detail::CliVisitor v{app, group};
  params.visit(v);
}

/// @brief Remembers an error met before run() (e.g. a bad --config file) so that run() reports
/// it with its exit code instead of the process aborting.
void deferError(std::exception_ptr error);

/// @brief Finds "--config FILE" / "--config=FILE" in argv before CLI11 parses, so that the
/// file's values become the defaults and command-line options override them. A bad file
/// (unknown key, wrong type: ConfigError; unreadable: IoError) is reported by run().
template <class Params>
void preloadConfig(int argc, char** argv, Params& params) {
  try {
    for (int i = 1; i < argc; ++i) {
      std::string arg = argv[i], file;
      if (arg == "--config" && i + 1 < argc)
        file = argv[i + 1];
      else if (arg.rfind("--config=", 0) == 0)
        file = arg.substr(9);
      if (!file.empty()) paramsFromJson(params, io::readDocument(file), file);
    }
  } catch (...) {
    deferError(std::current_exception());
  }
}

/// @brief Parses argv and runs `body`, turning every error into a one-line message on stderr
/// ("<tool>: error: ...") and the documented exit code. --help exits 0.
int run(CLI::App& app, int argc, char** argv, const std::function<void()>& body);

/// @brief Like run(), but first loads --config into `params` (config values become defaults,
/// command-line options override them) and validates the parameters before `body`.
template <class Params>
int runStage(CLI::App& app, int argc, char** argv, Params& params,
             const std::function<void()>& body) {
  preloadConfig(argc, argv, params);
  return run(app, argc, argv, [&] {
    params.validate();
    body();
  });
}

/// @brief Splits "a,b" or a list file ("@list.txt" or "-" for stdin, one path per line) into paths.
std::vector<std::string> expandInputList(const std::vector<std::string>& args);

}  // namespace mapfuse::cli
