#include "mapfuse/lidar/forest_thresholds.hpp"

#include <algorithm>
#include <limits>

namespace mapfuse::lidar {
namespace {
/// IoU over all drives pooled (sums of TP, FP and truth).
double pooledIou(const std::vector<ValidationSet>& drives, float t) {
  double tp = 0, fp = 0, truth = 0;
  for (const auto& d : drives) {
    const LabelSamples& v = d.samples;
    truth += static_cast<double>(v.truth_points);
    for (std::size_t i = 0; i < v.points.size(); ++i) {
      if (d.correct_votes[i] < t) continue;
      tp += v.correct_points[i];
      fp += v.points[i] - v.correct_points[i];
    }
  }
  return truth + fp > 0 ? tp / (truth + fp) : 0.0;
}
}  // namespace

double validationIou(const LabelSamples& v, const std::vector<float>& votes, float threshold) {
  double tp = 0, fp = 0;
  for (std::size_t i = 0; i < v.points.size(); ++i) {
    if (votes[i] < threshold) continue;
    tp += v.correct_points[i];
    fp += v.points[i] - v.correct_points[i];
  }
  const double denom = static_cast<double>(v.truth_points) + fp;
  return denom > 0 ? tp / denom : 0.0;
}

ThresholdChoice chooseThreshold(const std::vector<ValidationSet>& drives, double min_gain,
                                double tolerance) {
  ThresholdChoice c;
  std::vector<const ValidationSet*> voting;
  for (const auto& d : drives) {
    c.clusters += d.samples.points.size();
    if (d.samples.truth_points > 0) voting.push_back(&d);
  }
  if (voting.empty()) {
    c.reason = "no validation drive has true points of this label";
    return c;
  }
  c.validated = true;
  c.iou_unfiltered = pooledIou(drives, 0.0f);
  c.iou_majority = pooledIou(drives, 0.5f);
  double best = -std::numeric_limits<double>::infinity();
  float best_t = 0.5f;
  for (int k = 1; k <= 19; ++k) {
    const float t = 0.05f * static_cast<float>(k);
    double worst = std::numeric_limits<double>::infinity();
    for (const ValidationSet* d : voting)
      worst = std::min(worst, validationIou(d->samples, d->correct_votes, t) -
                                  validationIou(d->samples, d->correct_votes, 0.0f));
    c.worst_gain_by_threshold.push_back(worst);
    best = std::max(best, worst);
  }
  for (int k = 1; k <= 19; ++k)  // the lowest threshold on the best plateau
    if (c.worst_gain_by_threshold[k - 1] >= best - tolerance) {
      best_t = 0.05f * static_cast<float>(k);
      best = c.worst_gain_by_threshold[k - 1];
      break;
    }
  c.worst_gain = best;
  c.used = best >= min_gain;
  if (!c.used) {
    c.iou_filtered = c.iou_unfiltered;
    c.reason = "best worst-drive IoU gain " + std::to_string(100.0 * best) +
               " points (at threshold " + std::to_string(best_t) + ") below forest_min_gain";
    return c;
  }
  c.min_correct_votes = best_t;
  c.iou_filtered = pooledIou(drives, best_t);
  for (const auto& d : drives)
    for (std::size_t i = 0; i < d.samples.points.size(); ++i) {
      if (d.correct_votes[i] >= best_t) continue;
      ++c.rejected_clusters;
      c.rejected_correct_points += static_cast<std::size_t>(d.samples.correct_points[i]);
      c.rejected_wrong_points +=
          static_cast<std::size_t>(d.samples.points[i] - d.samples.correct_points[i]);
    }
  return c;
}

}  // namespace mapfuse::lidar
