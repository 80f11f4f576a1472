#include "mapfuse/cli/output_guard.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <system_error>

#include "mapfuse/cli/app.hpp"
#include "mapfuse/core/error.hpp"

namespace fs = std::filesystem;

namespace mapfuse::cli {

std::string resolvedPath(const std::string& p) {
  std::error_code ec;
  fs::path abs = fs::absolute(fs::path(p), ec);
  if (ec) return fs::path(p).lexically_normal().string();
  fs::path canon = fs::weakly_canonical(abs, ec);
  if (ec) canon = abs.lexically_normal();
  std::string s = canon.string();
  while (s.size() > 1 && s.back() == '/') s.pop_back();  // "a/b/" and "a/b" are one folder
  return s;
}

namespace {
/// Whether resolved path `inner` is `outer` or below it (whole components only).
bool atOrBelow(const std::string& inner, const std::string& outer) {
  if (inner == outer) return true;
  if (outer == "/") return true;
  return inner.size() > outer.size() && inner.compare(0, outer.size(), outer) == 0 &&
         inner[outer.size()] == '/';
}

/// Same file under two names (hard links, bind mounts) that resolving cannot see.
bool sameFile(const std::string& a, const std::string& b) {
  std::error_code ec;
  return fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec) && !ec;
}
}  // namespace

bool pathsOverlap(const std::string& out, const std::string& in) {
  if (out.empty() || in.empty()) return false;
  const std::string o = resolvedPath(out), i = resolvedPath(in);
  return atOrBelow(o, i) || atOrBelow(i, o) || sameFile(o, i);
}

void refuseOutputOverInputs(const std::string& out, const std::vector<std::string>& inputs) {
  for (const auto& in : inputs) {
    if (!pathsOverlap(out, in)) continue;
    const std::string o = resolvedPath(out), i = resolvedPath(in);
    std::string how = "is the input";
    if (o != i && atOrBelow(o, i))
      how = "lies inside the input";
    else if (o != i && atOrBelow(i, o))
      how = "contains the input";
    throw ConfigError("output '" + out + "' " + how + " '" + in + "' (resolved: " + o + " and " +
                      i + "); a tool never writes into what it reads: choose another -o");
  }
}

namespace {
bool isTextOption(const CLI::Option& opt) {
  const std::string type = opt.get_type_name();
  return type.find("TEXT") != std::string::npos || type.find("FILE") != std::string::npos ||
         type.find("DIR") != std::string::npos || type.find("PATH") != std::string::npos;
}

bool isOutOption(const CLI::Option& opt) {
  return opt.check_name("--out") || opt.check_name("-o");
}
}  // namespace

std::vector<std::string> inputPathsOf(const CLI::App& app) {
  std::vector<std::string> paths;
  for (const CLI::Option* opt : app.get_options()) {
    if (opt->count() == 0 || isOutOption(*opt) || !isTextOption(*opt)) continue;
    for (const std::string& v : opt->results()) {
      if (v.empty() || v == "-") continue;
      std::error_code ec;
      if (!fs::exists(v[0] == '@' ? v.substr(1) : v, ec)) continue;  // names, numbers, missing
      if (v[0] == '@') {
        paths.push_back(v.substr(1));
        if (fs::is_regular_file(v.substr(1), ec))
          for (auto& p : expandInputList({v})) paths.push_back(std::move(p));
        continue;
      }
      paths.push_back(v);
    }
  }
  return paths;
}

void checkOutputsOfCommandLine(const CLI::App& app) {
  const CLI::Option* out = app.get_option_no_throw("--out");
  if (out && out->count() > 0) {
    for (const std::string& o : out->results()) refuseOutputOverInputs(o, inputPathsOf(app));
  }
  for (const CLI::App* sub : app.get_subcommands()) checkOutputsOfCommandLine(*sub);
}

}  // namespace mapfuse::cli
