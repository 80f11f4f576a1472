#include "mapfuse/io/stage_report.hpp"

#include "mapfuse/io/document.hpp"

namespace mapfuse::io {

void writeResolvedConfig(const std::filesystem::path& dir, const std::string& stage,
                         const nlohmann::json& params) {
  writeDocument(dir / (stage + ".config.json"), params, 2);
}

void writeSummary(const std::filesystem::path& dir, const std::string& stage,
                  nlohmann::json summary) {
  summary["format"] = "mapfuse.summary";
  summary["stage"] = stage;
  summary["mapfuse_version"] = "0.1.0";
  writeDocument(dir / (stage + ".summary.json"), summary, 2);
}

}  // namespace mapfuse::io
