#include "mapfuse/io/align_registrations.hpp"

#include <map>

#include "mapfuse/io/document.hpp"

namespace mapfuse::io {

AlignRegistrations alignRegistrationsFromJson(const Json& doc, const std::string& file) {
  const JsonView v(doc, file);
  if (auto stage = v.find("stage"))
    if (stage->string() != "align") stage->fail("expected the summary of align");
  AlignRegistrations r;
  const JsonView inputs = v.at("inputs");
  for (std::size_t i = 0; i < inputs.size(); ++i) r.inputs.push_back(inputs.at(i).string());
  const JsonView pairs = v.at("pairs");
  const auto last = int64_t(r.inputs.size()) - 1;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const JsonView p = pairs.at(i);
    AlignRegistration reg;
    reg.kept = p.at("accepted").boolean() && p.at("pcm_consistent").boolean() &&
               !p.at("graph_outlier").boolean();
    const int64_t a = p.at("lsm_a").integer(), b = p.at("lsm_b").integer();
    if (a < 0 || b < 0 || a > last || b > last)
      p.fail("lsm_a / lsm_b outside the summary's " + std::to_string(r.inputs.size()) + " inputs");
    reg.lsm_a = std::size_t(a);
    reg.lsm_b = std::size_t(b);
    r.pairs.push_back(reg);
  }
  return r;
}

AlignRegistrations readAlignRegistrations(const std::filesystem::path& path) {
  return alignRegistrationsFromJson(readDocument(path), path.string());
}

std::vector<std::pair<int, int>> keptPairsAmong(const AlignRegistrations& summary,
                                                const std::vector<std::filesystem::path>& files) {
  std::map<std::string, int> index_of;  // file name -> index in `files`
  for (std::size_t i = 0; i < files.size(); ++i) index_of[files[i].filename().string()] = int(i);
  std::vector<int> index(summary.inputs.size(), -1);  // align's input -> index in `files`
  for (std::size_t i = 0; i < summary.inputs.size(); ++i) {
    const auto it = index_of.find(std::filesystem::path(summary.inputs[i]).filename().string());
    if (it != index_of.end()) index[i] = it->second;
  }
  std::vector<std::pair<int, int>> links;
  for (const auto& p : summary.pairs)
    if (p.kept && index[p.lsm_a] >= 0 && index[p.lsm_b] >= 0)
      links.emplace_back(index[p.lsm_a], index[p.lsm_b]);
  return links;
}

}  // namespace mapfuse::io
