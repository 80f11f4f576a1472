#pragma once
/// @file `evaluate changes` (docs/evaluate.md "evaluate changes"): detected map changes scored
/// against the true ones. A detected change matches a true one of the same kind and class:
/// removed / moved / restriped / retyped by the same before_id; added by the nearest centres
/// within `added_match_distance` (greedy, closest pairs first, each change matched once).
/// Precision, recall and F1 overall, per change kind and per class; detected removals of
/// elements no true change touched (false removals) counted separately, as a share of those
/// unchanged elements of the before map.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mapfuse/core/map_changes.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::eval {

struct ChangeScoreSettings {
  double added_match_distance = 3.0;      ///< m, detected and true additions' centres
  double max_false_removal_rate = 0.005;  ///< share of unchanged elements (issue 34: 0.5 %)

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("added_match_distance", added_match_distance, "m",
      "largest distance between the centres of a detected and a true addition that match",
      in(0.01, 100));
    v("max_false_removal_rate", max_false_removal_rate, "",
      "bound on false removals / unchanged elements; above it the summary says so and warns",
      in(0, 1));
  }
};

/// Matched (tp), unmatched detected (fp) and unmatched true (fn) changes of one group.
struct ChangeCounts {
  int tp = 0, fp = 0, fn = 0;
  std::optional<double> precision() const;  ///< tp / (tp + fp); none without detections
  std::optional<double> recall() const;     ///< tp / (tp + fn); none without true changes
  std::optional<double> f1() const;         ///< 2 tp / (2 tp + fp + fn); none when all are 0
};

/// One change that found no partner.
struct UnmatchedChange {
  ChangeKind kind;
  CrowdClass cls;
  std::optional<int64_t> before_id, after_id;
};

struct ChangeScores {
  ChangeCounts overall;
  std::map<ChangeKind, ChangeCounts> by_kind;   ///< every kind
  std::map<CrowdClass, ChangeCounts> by_class;  ///< every class
  int unchanged_elements = 0;                   ///< before-map elements no true change names
  int false_removals = 0;                       ///< detected removals of unchanged elements
  int false_other = 0;  ///< detected moves / restripes / retypes of unchanged elements
  std::vector<UnmatchedChange> missed;  ///< true changes not detected
  std::vector<UnmatchedChange> wrong;   ///< detected changes that match no true one
  /// false_removals / unchanged_elements; none without unchanged elements
  std::optional<double> falseRemovalRate() const;
};

/// @brief Checks that both change files describe `before`: the same origin (1e-7 deg, 1 mm) and
/// every before_id an element of `before` of the change's class.
/// @throws ParseError naming the file and the field (exit 3); InputError for another origin.
void checkAgainstBefore(const MapChanges& changes, const std::string& file, const VectorMap& before,
                        const std::string& before_file);

/// @brief Scores `detected` against `truth` (both checked with checkAgainstBefore).
ChangeScores scoreChanges(const MapChanges& detected, const MapChanges& truth,
                          const VectorMap& before, const ChangeScoreSettings& settings);

}  // namespace mapfuse::eval
