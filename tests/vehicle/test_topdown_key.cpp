// lsm-build's BEV picture key (issue 20): every class present in the LSM is in the legend.
#include <catch2/catch.hpp>
#include <set>

#include "mapfuse/vehicle/render_topdown.hpp"

using namespace mapfuse;

TEST_CASE("BEV key: each class of the LSM, the trajectory and keyframes are in the legend",
          "[vehicle][picture]") {
  Lsm lsm;
  lsm.drive_id = "d0";
  Keyframe k;
  k.id = 1;
  lsm.keyframes.push_back(k);
  int64_t id = 0;
  for (CrowdClass c :
       {CrowdClass::kLaneLine, CrowdClass::kPole, CrowdClass::kLaneLine, CrowdClass::kCrosswalk}) {
    Element e;
    e.id = ++id;
    e.cls = c;
    e.anchor = 1;
    e.points_body = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
    e.covariances.assign(3, Eigen::Matrix3d::Identity());
    lsm.elements.push_back(e);
  }
  const io::PictureKey key = vehicle::topDownKey(lsm, 0.05);
  std::set<std::string> labels;
  for (const auto& e : key.legend) labels.insert(e.label);
  CHECK(labels ==
        std::set<std::string>{"lane_line", "pole", "crosswalk", "trajectory", "keyframe"});
  CHECK(key.metres_per_pixel == 0.05);
  CHECK(key.title == "d0");
  // The picture with its key: the 200 px panel beside the rendering.
  const cv::Mat img = vehicle::renderTopDown(lsm, {Pose3::Identity()}, 0.05);
  CHECK(io::withPictureKey(img, key).cols == img.cols + 200);
}

TEST_CASE("BEV key: a north arrow only for an LSM in ENU", "[vehicle][picture]") {
  Lsm lsm;
  lsm.drive_id = "2011_09_26_drive_0001_sync";
  CHECK_FALSE(vehicle::topDownKey(lsm, 0.1).north_up);  // odometry frame: north unknown
  CHECK_FALSE(vehicle::topDownKey(lsm, 0.1).up_note.empty());
  lsm.frame = LsmFrame::kEnu;
  CHECK(vehicle::topDownKey(lsm, 0.1).north_up);
}
