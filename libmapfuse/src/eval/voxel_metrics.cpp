#include "mapfuse/eval/voxel_metrics.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace mapfuse::eval {

ConfusionMatrix& ConfusionMatrix::operator+=(const ConfusionMatrix& o) {
  for (int t = 0; t < kNumLidarClasses; ++t) {
    for (int p = 0; p < kNumLidarClasses; ++p) counts[t][p] += o.counts[t][p];
    spurious[t] += o.spurious[t];
  }
  return *this;
}

LabelScores scoreConfusion(const ConfusionMatrix& m) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  LabelScores s;
  double sum_acc = 0.0, sum_iou = 0.0;
  int n_acc = 0, n_iou = 0;
  for (int t = 1; t < kNumLidarClasses; ++t)
    for (int p = 0; p < kNumLidarClasses; ++p) s.evaluated += m.counts[t][p];
  for (std::size_t k = 0; k < kTable1Classes.size(); ++k) {
    const int c = static_cast<int>(kTable1Classes[k]);
    ClassScore& cs = s.classes[k];
    cs.cls = kTable1Classes[k];
    cs.tp = m.counts[c][c];
    // FP: predicted c where the truth is another labelled class or nothing should be;
    // FN: truth c predicted as anything else (including unlabeled / missing).
    for (int t = 1; t < kNumLidarClasses; ++t)
      if (t != c) cs.fp += m.counts[t][c];
    cs.fp += m.spurious[c];
    for (int p = 0; p < kNumLidarClasses; ++p)
      if (p != c) cs.fn += m.counts[c][p];
    cs.accuracy = (cs.tp + cs.fp) ? double(cs.tp) / double(cs.tp + cs.fp) : kNaN;  // eq. (10)
    cs.iou =
        (cs.tp + cs.fp + cs.fn) ? double(cs.tp) / double(cs.tp + cs.fp + cs.fn) : kNaN;  // eq. (11)
    if (!std::isnan(cs.accuracy)) sum_acc += cs.accuracy, ++n_acc;
    if (!std::isnan(cs.iou)) sum_iou += cs.iou, ++n_iou;
  }
  s.mean_accuracy = n_acc ? sum_acc / n_acc : kNaN;
  s.mean_iou = n_iou ? sum_iou / n_iou : kNaN;
  return s;
}

namespace {
nlohmann::json number(double x) {
  return std::isnan(x) ? nlohmann::json() : nlohmann::json(x);
}
std::string percent(double x) {
  if (std::isnan(x)) return "-";
  char buf[16];
  std::snprintf(buf, sizeof(buf), "%.1f", 100.0 * x);
  return buf;
}
}  // namespace

nlohmann::json scoresToJson(const LabelScores& s) {
  nlohmann::json classes = nlohmann::json::object();
  for (const auto& c : s.classes)
    classes[lidarClassName(c.cls)] = {{"tp", c.tp},
                                      {"fp", c.fp},
                                      {"fn", c.fn},
                                      {"accuracy", number(c.accuracy)},
                                      {"iou", number(c.iou)}};
  return {{"classes", classes},
          {"mean_accuracy", number(s.mean_accuracy)},
          {"mean_iou", number(s.mean_iou)},
          {"evaluated", s.evaluated}};
}

std::string scoresToMarkdown(const LabelScores& s, const std::string& title) {
  std::string head = "| " + title + " |", rule = "|---|", acc = "| Accuracy (%) |",
              iou = "| IoU (%) |";
  for (const auto& c : s.classes) {
    head += std::string(" ") + lidarClassName(c.cls) + " |";
    rule += "---:|";
    acc += " " + percent(c.accuracy) + " |";
    iou += " " + percent(c.iou) + " |";
  }
  head += " mean |";
  rule += "---:|";
  acc += " " + percent(s.mean_accuracy) + " |";
  iou += " " + percent(s.mean_iou) + " |";
  return head + "\n" + rule + "\n" + acc + "\n" + iou + "\n";
}

}  // namespace mapfuse::eval
