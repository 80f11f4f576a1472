#include "mapfuse/io/png_decode.hpp"

#include <cstring>
#include <opencv2/imgcodecs.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/bounds.hpp"

namespace mapfuse::io {
namespace {

uint32_t bigEndian32(const std::string& bytes, std::size_t at) {
  uint32_t v = 0;
  for (std::size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(bytes[at + k]);
  return v;
}

}  // namespace

cv::Mat decodePng(const std::string& bytes, const std::string& file, int flags) {
  // PNG: 8-byte signature, then the IHDR chunk (length, "IHDR", width, height: big-endian).
  static const char kSignature[] = "\x89PNG\r\n\x1a\n";
  if (bytes.size() < 24 || std::memcmp(bytes.data(), kSignature, 8) != 0 ||
      std::memcmp(bytes.data() + 12, "IHDR", 4) != 0)
    throw ParseError(file, "png", "not a PNG file");
  const int64_t width = bigEndian32(bytes, 16), height = bigEndian32(bytes, 20);
  if (width < 1 || height < 1 || width > bounds::kMaxImageSide || height > bounds::kMaxImageSide ||
      width * height > bounds::kMaxImagePixels)
    throw ParseError(file, "png",
                     "declares " + std::to_string(width) + "x" + std::to_string(height) +
                         " pixels (at most " + std::to_string(bounds::kMaxImageSide) +
                         " a side and " + std::to_string(bounds::kMaxImagePixels) + " in all)");
  cv::Mat img;
  try {
    const cv::Mat raw(1, static_cast<int>(bytes.size()), CV_8UC1, const_cast<char*>(bytes.data()));
    img = cv::imdecode(raw, flags);
  } catch (const cv::Exception&) {
    img = cv::Mat();
  }
  if (img.empty()) throw ParseError(file, "png", "not a decodable image (corrupt PNG?)");
  return img;
}

}  // namespace mapfuse::io
