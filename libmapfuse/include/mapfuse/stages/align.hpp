#pragma once
/// @file Stage `align` (§4.2, Song et al. 2023): reads georeferenced LSMs sharing one ENU origin,
/// runs fusion::alignLsms, writes the aligned LSMs, align.config.json and align.summary.json.
/// `--method` selects the Table 1 baseline.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mapfuse/fusion/align.hpp"

namespace mapfuse::stages {

struct AlignParams {
  static constexpr const char* kName = "AlignParams";
  fusion::AlignSettings align;

  template <class V>
  void visit(V& v) {
    align.visit(v);
  }
};

/// @brief The summary align.summary.json holds (paper Table 1 quantities, per-pair checks).
nlohmann::json toJson(const fusion::AlignResult& r);

/// @brief Aligns the LSMs; writes each to <out_dir>/<same file name>, align.config.json and
/// align.summary.json.
/// @throws InputError when an LSM is not in enu or origins differ; IoError / ParseError.
fusion::AlignResult runAlign(const std::vector<std::string>& inputs,
                             const std::filesystem::path& out_dir, const AlignParams& params);

}  // namespace mapfuse::stages
