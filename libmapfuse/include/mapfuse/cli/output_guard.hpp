#pragma once
/// @file No tool writes into what it reads (docs/cli.md "Outputs never overlap inputs"). Every
/// path is resolved first (absolute, symbolic links followed, `.` and `..` removed); then an
/// output path `out` and an input path `in` overlap when
///   - they are the same file or folder, or
///   - `out` lies below `in` (an input folder: a drive, a SemanticKITTI sequence, a tile), or
///   - `in` lies below `out` (the output folder holds an input at any depth).
/// The third rule is deliberately the whole folder, not only the names a tool writes today: a
/// tool owns its output folder as a set (it locks it, removes stale temporaries below it, and
/// writes names taken from its inputs: align/georef keep file names, tile/balance one folder per
/// tile), so no input below it is safe. Overlap is a usage error (exit 2) raised before any work,
/// naming both paths.
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace mapfuse::cli {

/// @brief `p` made absolute with links resolved as far as it exists (weakly canonical).
std::string resolvedPath(const std::string& p);

/// @brief Whether writing `out` may change `in` (same path, or one below the other, resolved).
bool pathsOverlap(const std::string& out, const std::string& in);

/// @brief Refuses an output that overlaps any input.
/// @throws ConfigError (exit 2) naming the output, the input and both resolved paths.
void refuseOutputOverInputs(const std::string& out, const std::vector<std::string>& inputs);

/// @brief The paths a parsed command line names, apart from -o/--out: the values of every text
/// option and positional (an `@list.txt` gives the list file and its entries; `-` is skipped:
/// stdin lists are checked by the tool once read).
std::vector<std::string> inputPathsOf(const CLI::App& app);

/// @brief For `app` and each parsed subcommand with -o/--out given: refuseOutputOverInputs(out,
/// inputPathsOf(that command)). Called by cli::run right after parsing.
void checkOutputsOfCommandLine(const CLI::App& app);

}  // namespace mapfuse::cli
