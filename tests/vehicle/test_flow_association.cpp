#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "mapfuse/vehicle/flow_association.hpp"

using namespace mapfuse;
using namespace mapfuse::vehicle;

TEST_CASE("optical flow carries track ids to the moved boxes of the next frame") {
  // Seeded random texture, shifted by (6, -3) px between the frames.
  cv::Mat noise(240, 320, CV_8UC1);
  std::mt19937_64 rng(9);
  for (int r = 0; r < noise.rows; ++r)
    for (int c = 0; c < noise.cols; ++c) noise.at<uint8_t>(r, c) = uint8_t(rng() % 256);
  cv::Mat prev;
  cv::GaussianBlur(noise, prev, {0, 0}, 2.0);
  cv::Mat next;
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, 6, 0, 1, -3);
  cv::warpAffine(prev, next, shift, prev.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);

  auto box = [](double u0, double v0, double u1, double v1, CrowdClass c) {
    AerialObservation a;
    a.cls = c;
    a.box = Eigen::Vector4d(u0, v0, u1, v1);
    return a;
  };
  std::vector<AerialObservation> a = {box(40, 40, 80, 100, CrowdClass::kTrafficSign),
                                      box(150, 60, 190, 100, CrowdClass::kTrafficSign),
                                      box(230, 120, 250, 200, CrowdClass::kPole)};
  a[0].track_id = 10, a[1].track_id = 11, a[2].track_id = 12;
  // Next frame: the same boxes moved (listed in another order) and one new box.
  std::vector<AerialObservation> b = {box(236, 117, 256, 197, CrowdClass::kPole),
                                      box(46, 37, 86, 97, CrowdClass::kTrafficSign),
                                      box(156, 57, 196, 97, CrowdClass::kTrafficSign),
                                      box(100, 150, 120, 170, CrowdClass::kTrafficSign)};
  int64_t next_id = 100;
  associateByFlow(prev, next, a, b, next_id, FlowSettings{});
  CHECK(b[0].track_id == 12);
  CHECK(b[1].track_id == 10);
  CHECK(b[2].track_id == 11);
  CHECK(b[3].track_id == 100);
  CHECK(next_id == 101);
  CHECK(boxIou(a[0].box, a[0].box) == Approx(1.0));
  CHECK(boxIou(a[0].box, a[1].box) == 0.0);
}
