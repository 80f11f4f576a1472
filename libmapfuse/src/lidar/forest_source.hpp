#pragma once
/// @file Which error-minimisation forests a map run uses, and where they came from: the setting
/// `classifier_dir` is "auto" (the forests the build generated next to the tools,
/// `<folder of the executable>/../models/lidar-classifiers`, see scripts/train-classifiers.sh),
/// "none" (error minimisation off) or a folder of rtrees_<label>.yml. The folder's
/// `provenance.json` (generator command, seeds, code commit, date, file sizes and hashes) is
/// carried into the run's summary.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "mapfuse/lidar/cluster_classifier.hpp"

namespace mapfuse::lidar {

/// The forests of a run (or why there are none).
struct ForestSource {
  ClusterClassifier classifier;  ///< empty when error minimisation is off
  std::filesystem::path dir;     ///< resolved folder (empty when off)
  nlohmann::json provenance;     ///< provenance.json of the folder; null when absent
  std::string skipped;           ///< why error minimisation is off; empty when it runs
};

/// @brief Folder the build writes the default forests to: `<folder of the running
/// executable>/../models/lidar-classifiers` (build/bin -> build/models; build/tests too).
std::filesystem::path defaultClassifierDir();

/// @brief Resolves `classifier_dir` ("auto", "none"/"" or a folder) and loads the forests.
/// "auto" without generated forests runs without error minimisation, with a warning naming the
/// folder and how to generate it; an explicit folder must exist.
/// @throws IoError when an explicit folder is missing; ParseError when a forest, thresholds.json
/// or provenance.json cannot be read.
ForestSource loadForests(const std::string& classifier_dir);

}  // namespace mapfuse::lidar
