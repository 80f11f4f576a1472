#include "forest_source.hpp"

#include <unistd.h>

#include <system_error>

#include "mapfuse/core/log.hpp"
#include "mapfuse/io/document.hpp"

namespace mapfuse::lidar {
namespace fs = std::filesystem;

fs::path defaultClassifierDir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  const fs::path bin = ec ? fs::current_path() : exe.parent_path();
  return (bin.parent_path() / "models" / "lidar-classifiers").lexically_normal();
}

ForestSource loadForests(const std::string& classifier_dir) {
  ForestSource src;
  if (classifier_dir.empty() || classifier_dir == "none") {
    src.skipped = "classifier_dir = \"none\"";
    return src;
  }
  src.dir = classifier_dir == "auto" ? defaultClassifierDir() : fs::path(classifier_dir);
  if (classifier_dir == "auto" && !fs::is_directory(src.dir)) {
    src.skipped = "no generated forests in " + src.dir.string() +
                  " (build target lidar_classifiers, or scripts/train-classifiers.sh)";
    MAPFUSE_WARN("lidar-semantic-map: error minimisation OFF: " << src.skipped);
    src.dir.clear();
    return src;
  }
  src.classifier = ClusterClassifier::load(src.dir);
  if (fs::exists(src.dir / "provenance.json"))
    src.provenance = io::readDocument(src.dir / "provenance.json");
  if (src.classifier.empty()) src.skipped = "no rtrees_<label>.yml in " + src.dir.string();
  return src;
}

}  // namespace mapfuse::lidar
