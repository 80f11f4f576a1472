#pragma once
/// @file Decoding PNG files held in memory, after checking the size their header declares: a
/// 100-byte PNG can declare 65535 x 65535 pixels, which the decoder would allocate before it
/// finds the data missing.
#include <opencv2/core.hpp>
#include <string>

namespace mapfuse::io {

/// @brief Decodes a PNG (cv::imdecode with `flags`).
/// @throws ParseError(file, "png") when the bytes are not a PNG, declare a side beyond
/// bounds::kMaxImageSide or more than bounds::kMaxImagePixels pixels, or do not decode.
cv::Mat decodePng(const std::string& bytes, const std::string& file, int flags);

}  // namespace mapfuse::io
