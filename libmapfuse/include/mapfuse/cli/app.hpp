#pragma once
/// @file Command-line conventions shared by every tool (docs/cli.md): --config FILE, one
/// --option per declared parameter with its default, unit and rule in --help, -v / --quiet, and
/// the mapping of errors to exit codes (0 ok, 1 internal, 2 usage/config, 3 bad input, 4 I/O).
/// A tool's main is a StageTool: its positional arguments, then run() with the library call; a
/// tool of subcommands (evaluate) is a CommandTool.
#include <CLI/CLI.hpp>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "mapfuse/cli/output_guard.hpp"
#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"

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

/// @brief "voxel edge [m] (voxel_size > 0)": a parameter's --help text.
std::string optionHelp(const char* help, const char* unit, const std::string& rule);

namespace detail {
struct CliVisitor {
  CLI::App& app;
  const char* group;
  template <class T>
  void operator()(const char* key, T& value, const char* unit, const char* help,
                  const param::Range& range) {
    app.add_option(optionName(key), value, optionHelp(help, unit, range.describe("")))
        ->capture_default_str()
        ->group(group);
  }
  template <class T>
  void operator()(const char* key, T& value, const char* unit, const char* help) {
    app.add_option(optionName(key), value, optionHelp(help, unit, ""))
        ->capture_default_str()
        ->group(group);
  }
  void operator()(const char* key, std::string& value, const char* unit, const char* help,
                  const param::OneOf& names) {
    app.add_option(optionName(key), value, optionHelp(help, unit, names.describe("")))
        ->capture_default_str()
        ->group(group);
  }
  void operator()(const char* key, std::string& value, const char* unit, const char* help,
                  const param::TextRule& rule) {
    app.add_option(optionName(key), value, optionHelp(help, unit, rule.text))
        ->capture_default_str()
        ->group(group);
  }
  /// A list of numbers: `--key 1.5,0.75` (or `--key 1.5 0.75`); the values replace the default.
  void operator()(const char* key, std::vector<double>& values, const char* unit, const char* help,
                  const param::ListRule& rule) {
    app.add_option(optionName(key), values, optionHelp(help, unit, rule.describe("")))
        ->delimiter(',')
        ->expected(1, static_cast<int>(rule.max_size))
        ->default_str(listDefault(values))
        ->group(group);
  }
  static std::string listDefault(const std::vector<double>& values);
  template <class E>
  void operator()(const char* key, E& value, const char* unit, const char* help,
                  const param::Names<E>& names) {
    // The option takes a name; an unknown name is a usage error naming the choices.
    app.add_option_function<std::string>(
           optionName(key),
           [&value, names, key](const std::string& name) {
             if (!names.find(name, &value))
               throw CLI::ValidationError(optionName(key),
                                          "\"" + name + "\" is not " + names.oneOf().describe(key));
           },
           optionHelp(help, unit, names.oneOf().describe("")))
        ->default_str(names.nameOf(value))
        ->group(group);
  }
  template <class T>
  void relation(const char*, const T&, bool, const char*) {}
};
}  // namespace detail

/// @brief One option per declared parameter, in the "Parameters" group of --help.
template <class Params>
void addParamOptions(CLI::App& app, Params& params, const char* group = "Parameters") {
  detail::CliVisitor v{app, group};
  params.visit(v);
}

/// @brief Remembers an error met before run() (e.g. a bad --config file) so that run() reports
/// it with its exit code instead of the process aborting.
void deferError(std::exception_ptr error);

/// @brief The file of "--config FILE" / "--config=FILE" in argv, or empty.
std::string configArgument(int argc, char** argv);

/// @brief Finds "--config FILE" / "--config=FILE" in argv before CLI11 parses, so that the
/// file's values become the defaults and command-line options override them. A bad file
/// (unknown key, wrong type, out of range, empty, not JSON: ConfigError; unreadable: IoError)
/// is reported by run().
template <class Params>
void preloadConfig(int argc, char** argv, Params& params) {
  try {
    const std::string file = configArgument(argc, argv);
    if (!file.empty()) paramsFromFile(params, file);
  } catch (...) {
    deferError(std::current_exception());
  }
}

/// @brief Parses argv and runs `body`, turning every error into a one-line message on stderr
/// ("<tool>: error: ...") and the documented exit code. --help exits 0.
int run(CLI::App& app, int argc, char** argv, const std::function<void()>& body);

/// @brief --help of a tool's positional LSM list.
inline constexpr const char* kLsmListHelp =
    "Input LSMs (.json/.cbor), @list.txt, or - for a list on stdin";

/// @brief Writes `line` and a newline to stdout.
void printLine(const std::string& line);

/// @brief Splits "a,b" or a list file ("@list.txt" or "-" for stdin, one path per line) into paths.
std::vector<std::string> expandInputList(const std::vector<std::string>& args);

/// A stage's command-line tool: its positional arguments and outputs (inputs(), out(), or
/// `app()` for anything else), then run(), which adds --config, -v, --quiet and one option per
/// parameter, parses, validates and calls `body`. A body that returns a string prints it as one
/// line on stdout (the path or figures a pipeline reads next).
///
///   cli::StageTool<stages::AlignParams> tool("align", apps::about::kAlign);
///   const auto& lsms = tool.inputs("lsms", cli::kLsmListHelp);
///   const auto& out = tool.out("Output folder");
///   return tool.run(argc, argv, [&](const auto& p) { stages::runAlign(lsms, out, p); return out;
///   });
template <class Params>
class StageTool {
 public:
  StageTool(const char* name, const char* description) : app_(description, name) {}
  StageTool(const StageTool&) = delete;
  StageTool& operator=(const StageTool&) = delete;

  CLI::App& app() { return app_; }
  Params& params() { return params_; }

  /// @brief A required positional list of input files ("a,b", @list.txt, or - for stdin).
  /// @return the paths, expanded by run() before the body runs.
  const std::vector<std::string>& inputs(const char* name, const char* help) {
    app_.add_option(name, inputs_, help)->required();
    return inputs_;
  }

  /// @brief The required -o/--out path. @return it, set once run() has parsed.
  const std::string& out(const char* help) {
    app_.add_option("-o,--out", out_, help)->required();
    return out_;
  }

  /// @brief A required option naming an existing file (e.g. --tiles). @return its path.
  const std::string& existingFile(const char* option, const char* help) {
    files_.emplace_back();
    app_.add_option(option, files_.back(), help)->required();  // missing: IoError, exit 4
    return files_.back();
  }

  /// @brief Adds the common options and the parameters, parses, validates, runs `body`.
  /// @return the process exit code.
  template <class Body>
  int run(int argc, char** argv, Body body) {
    addCommonOptions(app_, common_);
    preloadConfig(argc, argv, params_);  // file values become the defaults
    addParamOptions(app_, params_);
    return cli::run(app_, argc, argv, [&] {
      applyCommonOptions(common_);
      validateParams(params_);
      inputs_ = expandInputList(inputs_);
      refuseOutputOverInputs(out_, inputs_);  // lists read from stdin are known only now
      if constexpr (std::is_void_v<std::invoke_result_t<Body&, const Params&>>)
        body(std::as_const(params_));
      else
        printLine(body(std::as_const(params_)));
    });
  }

 private:
  CLI::App app_;
  Params params_;
  CommonOptions common_;
  std::vector<std::string> inputs_;
  std::string out_;
  std::deque<std::string> files_;  ///< stable addresses for existingFile()
};

/// @brief main() of a stage that reads a positional list of LSMs (`inputs_name`, @list.txt or -)
/// and writes below -o/--out: `body(lsms, out, params)` is the library call; what it returns is
/// printed as in StageTool::run.
template <class Params, class Body>
int lsmListMain(int argc, char** argv, const char* name, const char* about, const char* inputs_name,
                const char* out_help, Body body) {
  StageTool<Params> tool(name, about);
  const auto& lsms = tool.inputs(inputs_name, kLsmListHelp);
  const auto& out = tool.out(out_help);
  return tool.run(argc, argv, [&](const Params& params) { return body(lsms, out, params); });
}

/// @brief main() of a stage that turns LSMs into an output folder of LSMs with the same file
/// names (georef, align): `stage(lsms, out, params)` is the library call; prints the folder.
template <class Params, class Stage>
int lsmFolderMain(int argc, char** argv, const char* name, const char* about, Stage stage) {
  return lsmListMain<Params>(
      argc, argv, name, about, "lsms", "Output folder (LSMs keep their file names)",
      [&](const std::vector<std::string>& lsms, const std::string& out, const Params& params) {
        stage(lsms, out, params);
        return out;
      });
}

/// A tool of subcommands (`evaluate map`, `evaluate voxels`): each subcommand gets --config, -v
/// and --quiet, then its own options from its setup, which returns what runs when it is chosen.
///
///   cli::CommandTool tool("evaluate", apps::about::kEvaluate);
///   tool.add("map", "vector maps against the truth", setupMap);  // setupMap(sub) -> action
///   return tool.run(argc, argv);
class CommandTool {
 public:
  using Action = std::function<void()>;
  using Setup = std::function<Action(CLI::App& sub)>;

  CommandTool(const char* name, const char* description);

  /// @brief Adds subcommand `name` with the common options; `setup` adds the rest.
  void add(const std::string& name, const std::string& help, const Setup& setup);

  /// @brief Parses (exactly one subcommand), applies its -v / --quiet and runs its action.
  /// @return the process exit code.
  int run(int argc, char** argv);

 private:
  struct Command {
    CLI::App* sub = nullptr;
    std::unique_ptr<CommonOptions> common;  ///< bound to the subcommand's options
    Action action;
  };
  CLI::App app_;
  std::vector<Command> commands_;
};

/// @brief For a stage run as a subcommand, whose --config can only be read once parsing has told
/// which subcommand runs: the file's values replace the parameters not given on the command line
/// (as StageTool's preloaded defaults do), then every rule is checked.
/// @throws ConfigError naming the file or the parameter; IoError when the file cannot be read.
template <class Params>
void applyCommandConfig(CLI::App& sub, Params& params) {
  const std::string file = sub.get_option("--config")->template as<std::string>();
  if (!file.empty()) {
    Params from_file;
    paramsFromFile(from_file, file);  // checked here, so problems name the file
    const nlohmann::json loaded = paramsToJson(from_file);
    nlohmann::json unset = nlohmann::json::object();  // the keys not given on the command line
    for (auto it = loaded.begin(); it != loaded.end(); ++it)
      if (sub.get_option(optionName(it.key().c_str()))->count() == 0) unset[it.key()] = *it;
    paramsFromJson(params, unset, file);
  }
  validateParams(params);  // command-line values, relations
}

}  // namespace mapfuse::cli
