#pragma once
/// @file What later stages read of align.summary.json (docs/formats.md "Stage reports"): the
/// input files and, per registration, its two inputs and whether the pose graph kept it.
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "mapfuse/io/json_view.hpp"

namespace mapfuse::io {

struct AlignRegistration {
  std::size_t lsm_a = 0, lsm_b = 0;  ///< indices into AlignRegistrations::inputs
  /// accepted, PCM-consistent and not a graph outlier: the registration tied the two LSMs
  bool kept = false;
};

struct AlignRegistrations {
  std::vector<std::string> inputs;  ///< align's input files, in its order
  std::vector<AlignRegistration> pairs;
};

/// @brief The `inputs` and `pairs` (lsm_a, lsm_b, accepted, pcm_consistent, graph_outlier) of
/// an align summary; other keys are ignored. @throws ParseError naming `file` and the field
/// (missing, wrong type, an index outside the inputs).
AlignRegistrations alignRegistrationsFromJson(const Json& doc, const std::string& file);

/// @brief The registrations `summary` kept, as index pairs into `files` (matched to align's
/// inputs by file name; registrations of inputs not in `files` are left out).
std::vector<std::pair<int, int>> keptPairsAmong(const AlignRegistrations& summary,
                                                const std::vector<std::filesystem::path>& files);

/// @brief Reads and parses an align.summary.json. @throws IoError, ParseError.
AlignRegistrations readAlignRegistrations(const std::filesystem::path& path);

}  // namespace mapfuse::io
