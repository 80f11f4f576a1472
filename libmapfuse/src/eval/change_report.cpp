#include "mapfuse/eval/change_report.hpp"

#include <cstdio>

namespace mapfuse::eval {
namespace {

nlohmann::json orNull(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json();
}

nlohmann::json countsToJson(const ChangeCounts& c) {
  return {{"tp", c.tp},
          {"fp", c.fp},
          {"fn", c.fn},
          {"precision", orNull(c.precision())},
          {"recall", orNull(c.recall())},
          {"f1", orNull(c.f1())}};
}

nlohmann::json unmatchedToJson(const std::vector<UnmatchedChange>& list) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& u : list) {
    nlohmann::json j = {{"kind", changeKindName(u.kind)}, {"class", crowdClassName(u.cls)}};
    if (u.before_id) j["before_id"] = *u.before_id;
    if (u.after_id) j["after_id"] = *u.after_id;
    a.push_back(std::move(j));
  }
  return a;
}

std::string percent(const std::optional<double>& v) {
  if (!v) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", 100.0 * *v);
  return buf;
}

std::string row(const std::string& name, const ChangeCounts& c) {
  return "| " + name + " | " + std::to_string(c.tp) + " | " + std::to_string(c.fp) + " | " +
         std::to_string(c.fn) + " | " + percent(c.precision()) + " | " + percent(c.recall()) +
         " | " + percent(c.f1()) + " |\n";
}

bool empty(const ChangeCounts& c) {
  return c.tp + c.fp + c.fn == 0;
}

}  // namespace

nlohmann::json changeScoresToJson(const ChangeScores& s, const ChangeScoreSettings& settings) {
  nlohmann::json by_kind, by_class;
  for (const auto& [k, c] : s.by_kind) by_kind[changeKindName(k)] = countsToJson(c);
  for (const auto& [k, c] : s.by_class) by_class[crowdClassName(k)] = countsToJson(c);
  const auto rate = s.falseRemovalRate();
  return {{"overall", countsToJson(s.overall)},
          {"by_kind", by_kind},
          {"by_class", by_class},
          {"false_removals",
           {{"count", s.false_removals},
            {"unchanged_elements", s.unchanged_elements},
            {"rate", orNull(rate)},
            {"bound", settings.max_false_removal_rate},
            {"within_bound", !rate || *rate <= settings.max_false_removal_rate}}},
          {"false_other_changes", s.false_other},
          {"added_match_distance_m", settings.added_match_distance},
          {"missed", unmatchedToJson(s.missed)},
          {"wrong", unmatchedToJson(s.wrong)}};
}

std::string changeScoresToMarkdown(const ChangeScores& s, const ChangeScoreSettings& settings,
                                   const std::string& title) {
  std::string md = "| " + title + " | TP | FP | FN | precision (%) | recall (%) | F1 (%) |\n" +
                   "|---|---:|---:|---:|---:|---:|---:|\n" + row("all changes", s.overall);
  for (const auto& [k, c] : s.by_kind)
    if (!empty(c)) md += row(changeKindName(k), c);
  for (const auto& [k, c] : s.by_class)
    if (!empty(c)) md += row(crowdClassName(k), c);
  md += "\nFalse removals of unchanged elements: " + std::to_string(s.false_removals) + " of " +
        std::to_string(s.unchanged_elements) + " (" + percent(s.falseRemovalRate()) + " %, bound " +
        percent(settings.max_false_removal_rate) +
        " %); other false changes of "
        "unchanged elements: " +
        std::to_string(s.false_other) + ".\n";
  return md;
}

std::vector<std::string> changeInputProblems(const ChangeScores& s, const std::string& truth_file) {
  std::vector<std::string> problems;
  if (s.overall.tp + s.overall.fn == 0)
    problems.push_back(truth_file + " lists no change: recall and F1 are undefined");
  if (s.unchanged_elements == 0)
    problems.push_back(
        "every element of the before map changed: the false removal rate is "
        "undefined");
  return problems;
}

}  // namespace mapfuse::eval
