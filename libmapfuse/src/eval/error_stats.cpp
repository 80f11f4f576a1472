#include "mapfuse/eval/error_stats.hpp"

#include <algorithm>
#include <cmath>

namespace mapfuse::eval {

ErrorStats errorStats(std::vector<double> errors) {
  ErrorStats s;
  s.count = errors.size();
  if (errors.empty()) return s;
  std::sort(errors.begin(), errors.end());
  double sum = 0, sq = 0;
  for (double e : errors) sum += e, sq += e * e;
  s.mean = sum / double(errors.size());
  s.rms = std::sqrt(sq / double(errors.size()));
  constexpr double kThreeSigmaQuantile = 0.9973;
  const std::size_t rank =
      std::size_t(std::ceil(kThreeSigmaQuantile * double(errors.size())));  // nearest rank
  s.p3sigma = errors[std::min(errors.size(), std::max<std::size_t>(rank, 1)) - 1];
  s.max = errors.back();
  return s;
}

nlohmann::json toJson(const ErrorStats& s) {
  if (s.count == 0)
    return {
        {"count", 0}, {"mean", nullptr}, {"rms", nullptr}, {"p3sigma", nullptr}, {"max", nullptr}};
  return {
      {"count", s.count}, {"mean", s.mean}, {"rms", s.rms}, {"p3sigma", s.p3sigma}, {"max", s.max}};
}

}  // namespace mapfuse::eval
