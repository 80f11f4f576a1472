// PNG encoder: decoded by an independent decoder (OpenCV's imgcodecs, libpng) back to the same
// pixels for grey, BGR and BGRA images whose rows exercise every filter type; bad inputs throw.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <random>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/png_frames.hpp"
#include "mapfuse/io/png_writer.hpp"

using namespace mapfuse;

namespace {

/// Rows of different character: constant (None/Sub), vertical copies (Up), gradients
/// (Average/Paeth) and noise, so that the per-row filter choice varies.
cv::Mat testImage(int type) {
  cv::Mat img(37, 53, type);
  std::mt19937 rng(7);
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols * img.channels(); ++x) {
      uint8_t v;
      switch (y % 4) {
        case 0: v = 200; break;
        case 1: v = static_cast<uint8_t>(x * 3 + y); break;
        case 2: v = img.ptr<uint8_t>(y - 1)[x]; break;
        default: v = static_cast<uint8_t>(rng()); break;
      }
      img.ptr<uint8_t>(y)[x] = v;
    }
  return img;
}

}  // namespace

TEST_CASE("png writer: decodes to the same pixels", "[io][png]") {
  for (const int type : {CV_8UC1, CV_8UC3, CV_8UC4}) {
    const cv::Mat img = testImage(type);
    const std::string png = io::encodePng(img);
    REQUIRE(png.substr(0, 8) == std::string("\x89PNG\r\n\x1a\n", 8));
    const std::vector<uchar> bytes(png.begin(), png.end());
    const cv::Mat back = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
    REQUIRE(back.type() == type);
    REQUIRE(back.size() == img.size());
    CHECK(cv::countNonZero(back.reshape(1) != img.reshape(1)) == 0);
  }
}

TEST_CASE("png writer: writes atomically and rejects what PNG cannot hold", "[io][png]") {
  const auto dir = std::filesystem::temp_directory_path() / "mapfuse_png_writer_test";
  std::filesystem::create_directories(dir);
  const cv::Mat img = testImage(CV_8UC3);
  io::writePng(dir / "a.png", img);
  const cv::Mat back = cv::imread((dir / "a.png").string(), cv::IMREAD_UNCHANGED);
  CHECK(cv::countNonZero(back.reshape(1) != img.reshape(1)) == 0);
  CHECK_THROWS_AS(io::encodePng(cv::Mat()), InputError);
  CHECK_THROWS_AS(io::encodePng(cv::Mat(4, 4, CV_16UC1, cv::Scalar(1))), InputError);
  CHECK_THROWS_AS(io::encodePng(cv::Mat(4, 4, CV_8UC2, cv::Scalar(1, 2))), InputError);
  std::filesystem::remove_all(dir);
}

TEST_CASE("png frames: OpenCV's encoder, written atomically", "[io][png]") {
  const auto dir = std::filesystem::temp_directory_path() / "mapfuse_png_frames_test";
  std::filesystem::create_directories(dir);
  for (const int type : {CV_8UC1, CV_8UC3, CV_16UC1}) {
    cv::Mat img = testImage(CV_8UC1);
    if (type == CV_16UC1) img.convertTo(img, CV_16UC1, 257.0);
    if (type == CV_8UC3) img = testImage(CV_8UC3);
    io::writePngFrame(dir / "f.png", img);
    const cv::Mat back = cv::imread((dir / "f.png").string(), cv::IMREAD_UNCHANGED);
    REQUIRE(back.type() == type);
    CHECK(cv::countNonZero(back.reshape(1) != img.reshape(1)) == 0);
  }
  // A failed encode names the file and leaves the picture already there untouched.
  const std::string before = io::readBytes(dir / "f.png");
  CHECK_THROWS_WITH(io::writePngFrame(dir / "f.png", cv::Mat()), Catch::Contains("f.png"));
  CHECK(io::readBytes(dir / "f.png") == before);
  std::filesystem::remove_all(dir);
}
