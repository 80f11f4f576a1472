#include "mapfuse/lidar/cluster_classifier.hpp"

#include <unistd.h>

#include <cmath>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/ml.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/output_transaction.hpp"

namespace mapfuse::lidar {
namespace fs = std::filesystem;

struct ClusterClassifier::Impl {
  std::array<cv::Ptr<cv::ml::RTrees>, kNumLidarClasses> forests;
  std::array<float, kNumLidarClasses> thresholds;
  std::array<bool, kNumLidarClasses> removed{};  ///< dropped on validation
  Impl() { thresholds.fill(0.5f); }
};

ClusterClassifier::ClusterClassifier() : impl_(std::make_unique<Impl>()) {}
ClusterClassifier::~ClusterClassifier() = default;
ClusterClassifier::ClusterClassifier(ClusterClassifier&&) noexcept = default;
ClusterClassifier& ClusterClassifier::operator=(ClusterClassifier&&) noexcept = default;

namespace {
fs::path forestPath(const fs::path& dir, int label) {
  return dir / ("rtrees_" + std::string(lidarClassName(static_cast<LidarClass>(label))) + ".yml");
}
cv::Mat row(const ClusterFeatures& f) {
  return cv::Mat(1, kNumClusterFeatures, CV_32F, const_cast<float*>(f.data())).clone();
}
const char* const kThresholdsFile = "thresholds.json";

/// Reads `thresholds.json`: {"labels": {"<name>": {"min_correct_votes": x} or
/// {"forest_used": false}}}; a label marked unused is not filtered, even if a forest file of an
/// earlier training is still in the folder.
void loadThresholds(const fs::path& p, std::array<float, kNumLidarClasses>& out,
                    std::array<bool, kNumLidarClasses>& removed) {
  const nlohmann::json doc = io::readDocument(p);
  if (!doc.contains("labels") || !doc["labels"].is_object())
    throw ParseError(p.string(), "labels", "missing or not an object");
  for (int l = 1; l < kNumLidarClasses; ++l) {
    const std::string name = lidarClassName(static_cast<LidarClass>(l));
    if (!doc["labels"].contains(name)) continue;
    const auto& j = doc["labels"][name];
    if (j.contains("forest_used") && j["forest_used"] == false) removed[l] = true;
    if (!j.contains("min_correct_votes")) continue;
    const auto& t = j["min_correct_votes"];
    if (!t.is_number() || !(t.get<double>() >= 0.0 && t.get<double>() <= 1.0))
      throw ParseError(p.string(), "labels." + name + ".min_correct_votes",
                       "must be a number in [0, 1]");
    out[l] = t.get<float>();
  }
}
}  // namespace

ClusterClassifier ClusterClassifier::load(const fs::path& dir) {
  if (!fs::is_directory(dir)) throw IoError(dir.string(), "classifier folder not found");
  ClusterClassifier c;
  for (int l = 0; l < kNumLidarClasses; ++l) {
    const fs::path p = forestPath(dir, l);
    if (!fs::exists(p)) continue;
    try {
      auto forest = cv::ml::RTrees::load(p.string());
      if (forest.empty() || !forest->isTrained())
        throw ParseError(p.string(), "", "not a trained OpenCV RTrees model");
      if (forest->getVarCount() != kNumClusterFeatures)
        throw ParseError(p.string(), "var_count",
                         "expects " + std::to_string(forest->getVarCount()) + " features, not " +
                             std::to_string(kNumClusterFeatures));
      c.impl_->forests[l] = forest;
    } catch (const cv::Exception& e) {
      throw ParseError(p.string(), "", std::string("OpenCV cannot load the forest: ") + e.what());
    }
  }
  if (fs::exists(dir / kThresholdsFile))
    loadThresholds(dir / kThresholdsFile, c.impl_->thresholds, c.impl_->removed);
  for (int l = 0; l < kNumLidarClasses; ++l)
    if (c.impl_->removed[l]) c.impl_->forests[l].release();
  return c;
}

ClusterClassifier ClusterClassifier::train(
    const std::array<LabelSamples, kNumLidarClasses>& samples, const RTreesSettings& s,
    TrainingReport* report) {
  ClusterClassifier c;
  TrainingReport rep;
  for (int l = 0; l < kNumLidarClasses; ++l) {
    const LabelSamples& ls = samples[l];
    for (int y : ls.correct) (y ? rep.positives[l] : rep.negatives[l])++;
    if (rep.positives[l] < s.min_samples_per_class || rep.negatives[l] < s.min_samples_per_class)
      continue;
    cv::Mat X(static_cast<int>(ls.features.size()), kNumClusterFeatures, CV_32F);
    cv::Mat Y(static_cast<int>(ls.features.size()), 1, CV_32S);
    for (std::size_t i = 0; i < ls.features.size(); ++i) {
      row(ls.features[i]).copyTo(X.row(static_cast<int>(i)));
      Y.at<int>(static_cast<int>(i)) = ls.correct[i];
    }
    cv::setRNGSeed(static_cast<int>(s.seed + static_cast<uint64_t>(l)));
    auto forest = cv::ml::RTrees::create();
    if (s.balanced) {  // priors inverse to the class counts: both classes weigh the same
      const float n = static_cast<float>(X.rows);
      forest->setPriors(cv::Mat(cv::Matx12f(n / (2.0f * static_cast<float>(rep.negatives[l])),
                                            n / (2.0f * static_cast<float>(rep.positives[l])))));
    }
    forest->setMaxDepth(s.max_depth);
    forest->setMinSampleCount(s.min_sample_count);
    forest->setActiveVarCount(0);
    forest->setTermCriteria(cv::TermCriteria(cv::TermCriteria::MAX_ITER, s.num_trees, 0.0));
    forest->train(cv::ml::TrainData::create(X, cv::ml::ROW_SAMPLE, Y));
    int hits = 0;
    for (int i = 0; i < X.rows; ++i)
      hits += (forest->predict(X.row(i)) > 0.5f) == (Y.at<int>(i) == 1);
    rep.training_accuracy[l] = static_cast<double>(hits) / X.rows;
    rep.trained[l] = true;
    c.impl_->forests[l] = forest;
  }
  if (report) *report = rep;
  return c;
}

void ClusterClassifier::save(const fs::path& dir) const {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw IoError(dir.string(), "cannot create folder: " + ec.message());
  for (int l = 0; l < kNumLidarClasses; ++l) {
    if (!impl_->forests[l]) continue;
    const fs::path target = forestPath(dir, l);
    const fs::path tmp = target.string() + ".tmp-" + std::to_string(::getpid()) + ".yml";
    try {
      impl_->forests[l]->save(tmp.string());
    } catch (const cv::Exception& e) {
      fs::remove(tmp, ec);
      throw IoError(tmp.string(), std::string("cannot write forest: ") + e.what());
    }
    if (auto* outputs = io::OutputTransaction::active()) {  // replaced with the run's set
      outputs->stage(tmp, target);
      continue;
    }
    fs::rename(tmp, target, ec);
    if (ec) throw IoError(target.string(), "cannot rename temporary file: " + ec.message());
  }
  nlohmann::json labels = nlohmann::json::object();
  for (int l = 0; l < kNumLidarClasses; ++l)
    if (impl_->forests[l])
      labels[lidarClassName(static_cast<LidarClass>(l))] = {
          // 0.15, not 0.15000000596
          {"min_correct_votes", std::round(1e4 * double(impl_->thresholds[l])) / 1e4}};
    else if (impl_->removed[l])
      labels[lidarClassName(static_cast<LidarClass>(l))] = {{"forest_used", false}};
  io::writeBytesAtomic(
      dir / kThresholdsFile,
      nlohmann::json({{"format", "mapfuse.lidar_forest_thresholds"}, {"labels", labels}}).dump(2) +
          "\n");
}

bool ClusterClassifier::empty() const {
  for (const auto& f : impl_->forests)
    if (f) return false;
  return true;
}

bool ClusterClassifier::has(LidarClass label) const {
  return static_cast<bool>(impl_->forests[static_cast<int>(label)]);
}

std::vector<std::string> ClusterClassifier::labels() const {
  std::vector<std::string> out;
  for (int l = 0; l < kNumLidarClasses; ++l)
    if (impl_->forests[l]) out.push_back(lidarClassName(static_cast<LidarClass>(l)));
  return out;
}

float ClusterClassifier::correctVotes(LidarClass label, const ClusterFeatures& features) const {
  const auto& f = impl_->forests[static_cast<int>(label)];
  if (!f) return 1.0f;
  cv::Mat votes;  // row 0: the class values; row 1: the votes for each
  f->getVotes(row(features), votes, 0);
  int correct = 0, total = 0;
  for (int k = 0; k < votes.cols; ++k) {
    total += votes.at<int>(1, k);
    if (votes.at<int>(0, k) == 1) correct += votes.at<int>(1, k);
  }
  return total > 0 ? static_cast<float>(correct) / static_cast<float>(total) : 1.0f;
}

bool ClusterClassifier::accept(LidarClass label, const ClusterFeatures& features) const {
  if (!impl_->forests[static_cast<int>(label)]) return true;
  return correctVotes(label, features) >= impl_->thresholds[static_cast<int>(label)];
}

float ClusterClassifier::threshold(LidarClass label) const {
  return impl_->thresholds[static_cast<int>(label)];
}

void ClusterClassifier::setThreshold(LidarClass label, float min_correct_votes) {
  impl_->thresholds[static_cast<int>(label)] = min_correct_votes;
}

void ClusterClassifier::remove(LidarClass label) {
  impl_->forests[static_cast<int>(label)].release();
  impl_->removed[static_cast<int>(label)] = true;
}

}  // namespace mapfuse::lidar
