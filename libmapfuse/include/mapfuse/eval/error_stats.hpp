#pragma once
/// @file Summary statistics of a set of non-negative errors (docs/evaluate.md).
#include <cstddef>
#include <nlohmann/json.hpp>
#include <vector>

namespace mapfuse::eval {

struct ErrorStats {
  std::size_t count = 0;
  double mean = 0.0;     ///< mean of the errors
  double rms = 0.0;      ///< sqrt(mean of squares)
  double p3sigma = 0.0;  ///< "3 sigma" bound: the 99.73 % nearest-rank quantile of the errors
  double max = 0.0;
};

/// @brief Statistics of `errors` (all zero when empty).
ErrorStats errorStats(std::vector<double> errors);

/// @brief {"count", "mean", "rms", "p3sigma", "max"}; mean/rms/p3sigma/max null when count = 0.
nlohmann::json toJson(const ErrorStats& s);

}  // namespace mapfuse::eval
