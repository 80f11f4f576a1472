// Error minimisation's per-label rule (lidar/forest_thresholds.hpp): the validation IoU of a
// threshold against hand counts, a forest with skill kept at the IoU-best threshold, a forest
// that only costs its label dropped; thresholds.json round trip; the default forests.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <opencv2/core.hpp>

#include "mapfuse/core/error.hpp"

#include "lidar/forest_source.hpp"
#include "mapfuse/lidar/forest_thresholds.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
using namespace mapfuse::lidar;
namespace fs = std::filesystem;

namespace {
constexpr double kIouTol = 1e-12;  // exact ratios of integer counts

/// Validation clusters: (points, truly-of-the-label points) per cluster; truth = all
/// projected points truly of the label.
LabelSamples samples(const std::vector<std::pair<int, int>>& clusters, std::size_t truth) {
  LabelSamples s;
  for (const auto& [n, ok] : clusters) {
    s.features.push_back(ClusterFeatures{});
    s.correct.push_back(2 * ok > n ? 1 : 0);
    s.points.push_back(n);
    s.correct_points.push_back(ok);
  }
  s.truth_points = truth;
  return s;
}
}  // namespace

TEST_CASE("validation IoU of a threshold matches hand counts", "[lidar][forest]") {
  // Clusters: 100 points all correct, 50 points 10 correct, 20 points all wrong; 150 truth.
  const LabelSamples v = samples({{100, 100}, {50, 10}, {20, 0}}, 150);
  const std::vector<float> votes = {0.9f, 0.3f, 0.1f};
  // Nothing dropped: TP 110, FP 60 -> 110 / (150 + 60).
  CHECK(validationIou(v, votes, 0.0f) == Approx(110.0 / 210.0).margin(kIouTol));
  // Threshold 0.2 drops the 20-point cluster: TP 110, FP 40.
  CHECK(validationIou(v, votes, 0.2f) == Approx(110.0 / 190.0).margin(kIouTol));
  // Threshold 0.5 keeps only the first: TP 100, FP 0.
  CHECK(validationIou(v, votes, 0.5f) == Approx(100.0 / 150.0).margin(kIouTol));
  // Threshold 0.95 drops everything.
  CHECK(validationIou(v, votes, 0.95f) == 0.0);
}

TEST_CASE("a forest with skill filters at its IoU-best threshold", "[lidar][forest]") {
  const LabelSamples v = samples({{100, 100}, {50, 10}, {20, 0}}, 150);
  const ThresholdChoice c = chooseThreshold({{v, {0.9f, 0.3f, 0.1f}}}, 0.005);
  REQUIRE(c.used);
  // 0.35..0.9 all give 100/150; the lowest of them is chosen (fewest clusters dropped).
  CHECK(c.min_correct_votes == Approx(0.35f));
  CHECK(c.iou_filtered == Approx(100.0 / 150.0).margin(kIouTol));
  CHECK(c.iou_unfiltered == Approx(110.0 / 210.0).margin(kIouTol));
  CHECK(c.worst_gain == Approx(100.0 / 150.0 - 110.0 / 210.0).margin(kIouTol));
  CHECK(c.rejected_clusters == 2);
  CHECK(c.rejected_correct_points == 10);
  CHECK(c.rejected_wrong_points == 60);
}

TEST_CASE("on a plateau of gains the lowest threshold wins", "[lidar][forest]") {
  // 0.35 drops the 50-point cluster (IoU 100/151); 0.55 also the 1-point one (100/150):
  // 0.44 IoU points more, within a tolerance of 0.5 points.
  const LabelSamples v = samples({{100, 100}, {50, 10}, {1, 0}}, 150);
  const std::vector<ValidationSet> d = {{v, {0.9f, 0.3f, 0.5f}}};
  CHECK(chooseThreshold(d, 0.001, 0.0).min_correct_votes == Approx(0.55f));
  const ThresholdChoice c = chooseThreshold(d, 0.001, 0.005);
  CHECK(c.min_correct_votes == Approx(0.35f));
  CHECK(c.worst_gain == Approx(100.0 / 151.0 - 110.0 / 191.0).margin(kIouTol));
}

TEST_CASE("a forest that only costs its label is not used", "[lidar][forest]") {
  // The forest votes "wrong" for the big, correct clusters.
  const LabelSamples v = samples({{200, 190}, {150, 140}, {10, 0}}, 400);
  const ThresholdChoice c = chooseThreshold({{v, {0.2f, 0.1f, 0.4f}}}, 0.005);
  CHECK_FALSE(c.used);
  CHECK(c.iou_filtered == c.iou_unfiltered);
  CHECK(c.iou_unfiltered == Approx(330.0 / 430.0).margin(kIouTol));
  CHECK_FALSE(c.reason.empty());
  // A gain below forest_min_gain is not enough either: dropping the 10 wrong points gains
  // 330/420 - 330/430 = 1.8 IoU points.
  CHECK_FALSE(chooseThreshold({{v, {0.9f, 0.9f, 0.1f}}}, 0.02).used);
  CHECK(chooseThreshold({{v, {0.9f, 0.9f, 0.1f}}}, 0.01).used);
  CHECK_FALSE(chooseThreshold({{samples({}, 0), {}}}, 0.0).validated);
}

TEST_CASE("the threshold must not cost the label on any validation drive", "[lidar][forest]") {
  // The fence case of issue 24: at 0.5 the forest helps on drive a and erases the label on
  // drive b, whose correct clusters get 0.15-0.2 of the votes; 0.1 helps on both.
  const LabelSamples a = samples({{100, 100}, {50, 0}}, 120);
  const LabelSamples b = samples({{40, 40}, {30, 0}}, 50);
  const std::vector<ValidationSet> both = {{a, {0.9f, 0.05f}}, {b, {0.15f, 0.05f}}};
  CHECK(validationIou(b, both[1].correct_votes, 0.5f) == 0.0);  // majority vote erases b's
  const ThresholdChoice c = chooseThreshold(both, 0.001);
  REQUIRE(c.used);
  CHECK(c.min_correct_votes == Approx(0.1f));
  // worst of a's gain 100/120 - 100/170 and b's 40/50 - 40/80
  CHECK(c.worst_gain == Approx(100.0 / 120.0 - 100.0 / 170.0).margin(kIouTol));
  // From 0.2 on, drive b loses its label: the worst gain is negative there.
  CHECK(c.worst_gain_by_threshold[3] < 0.0);
  // A drive without true points of the label does not vote.
  const LabelSamples none = samples({{10, 0}}, 0);
  CHECK(chooseThreshold({both[0], both[1], {none, {0.01f}}}, 0.001).min_correct_votes ==
        Approx(0.1f));
}

TEST_CASE("thresholds.json round trip, a dropped label stays unfiltered", "[lidar][forest]") {
  const fs::path dir = test::tempDir("forest_thresholds");
  std::array<LabelSamples, kNumLidarClasses> train;
  cv::RNG rng(7);
  // Road and fence: every feature of a correct cluster in [5, 10), of a wrong one in [0, 2)
  // (each tree draws a few features per split: all of them separate the two).
  for (int l : {1, 4}) {
    for (int i = 0; i < 40; ++i) {
      const int ok = i % 2;
      ClusterFeatures f{};
      for (float& x : f)
        x = static_cast<float>(ok ? rng.uniform(5.0, 10.0) : rng.uniform(0.0, 2.0));
      train[l].features.push_back(f);
      train[l].correct.push_back(ok);
    }
  }
  RTreesSettings s;
  s.num_trees = 10;
  ClusterClassifier c = ClusterClassifier::train(train, s, nullptr);
  REQUIRE(c.has(LidarClass::kRoad));
  REQUIRE(c.has(LidarClass::kFence));
  ClusterFeatures longf{}, shortf{};
  longf.fill(8.0f);
  shortf.fill(1.0f);
  CHECK(c.correctVotes(LidarClass::kRoad, longf) > 0.9f);
  CHECK(c.correctVotes(LidarClass::kRoad, shortf) < 0.1f);
  c.setThreshold(LidarClass::kRoad, 0.05f);
  c.save(dir);  // writes rtrees_fence.yml
  c.remove(LidarClass::kFence);
  c.save(dir);  // the old rtrees_fence.yml stays on disk, thresholds.json marks it unused
  REQUIRE(fs::exists(dir / "rtrees_fence.yml"));
  const ClusterClassifier back = ClusterClassifier::load(dir);
  CHECK(back.has(LidarClass::kRoad));
  CHECK_FALSE(back.has(LidarClass::kFence));
  CHECK(back.threshold(LidarClass::kRoad) == Approx(0.05f));
  CHECK(back.accept(LidarClass::kFence, shortf));
}

TEST_CASE("classifier_dir auto finds the forests the build generated", "[lidar][forest]") {
  const ForestSource off = loadForests("none");
  CHECK(off.classifier.empty());
  CHECK_FALSE(off.skipped.empty());
  const fs::path dir = defaultClassifierDir();
  CHECK(dir.filename() == "lidar-classifiers");
  if (!MAPFUSE_FORESTS_GENERATED) std::exit(77);  // built without them: ctest says skipped
  REQUIRE(fs::exists(dir / "provenance.json"));   // target lidar_classifiers
  const ForestSource src = loadForests("auto");
  CHECK(src.skipped.empty());
  CHECK_FALSE(src.classifier.empty());
  CHECK(src.provenance["format"] == "mapfuse.lidar_forest_provenance");
  // Every generated file is listed with its size; sizes match the files.
  for (const auto& [name, f] : src.provenance["files"].items())
    CHECK(fs::file_size(dir / name) == f["bytes"].get<std::uintmax_t>());
  CHECK_THROWS_AS(loadForests((dir / "absent").string()), IoError);
}
