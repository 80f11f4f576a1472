#include "mapfuse/lidar/cluster_classifier.hpp"

#include <unistd.h>

#include <opencv2/core.hpp>
#include <opencv2/ml.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/output_transaction.hpp"

namespace mapfuse::lidar {
namespace fs = std::filesystem;

struct ClusterClassifier::Impl {
  std::array<cv::Ptr<cv::ml::RTrees>, kNumLidarClasses> forests;
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

bool ClusterClassifier::accept(LidarClass label, const ClusterFeatures& features) const {
  const auto& f = impl_->forests[static_cast<int>(label)];
  if (!f) return true;
  return f->predict(row(features)) > 0.5f;
}

}  // namespace mapfuse::lidar
