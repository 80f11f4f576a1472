#pragma once
/// @file Precomputed per-frame semantics for the LiDAR pipeline (docs/lidar.md, "Semantics
/// format"). Folder `<drive>/semantics_02/` beside `image_02/`; per frame either
///  - `<frame>.png`: single-channel 8-bit label image, values = LiDAR class ids 0..7
///    (core/classes.hpp LidarClass order), or
///  - `<frame>.prob`: ASCII header line `mapfuse-prob 1 <width> <height> <channels>\n`, then
///    width*height*channels uint8 (row-major, channel fastest), probability = value / 255,
///    channels = the 8 LiDAR classes.
/// When both exist, `.prob` wins.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace mapfuse::io {

/// Per-pixel class evidence of one camera frame: either hard labels or quantised probabilities.
struct SemanticImage {
  int width = 0;     ///< px
  int height = 0;    ///< px
  int channels = 0;  ///< 0 = label image (one class id per pixel), else probability channels
  std::vector<uint8_t> data;  ///< labels: width*height; probabilities: width*height*channels

  bool isLabels() const { return channels == 0; }
  /// @brief Label of pixel (u, v) (label image only).
  uint8_t label(int u, int v) const { return data[static_cast<std::size_t>(v) * width + u]; }
  /// @brief Pointer to the `channels` quantised probabilities of pixel (u, v).
  const uint8_t* prob(int u, int v) const {
    return data.data() + (static_cast<std::size_t>(v) * width + u) * channels;
  }

  /// @brief A label image; `labels` must hold width*height LiDAR class ids (0..7).
  static SemanticImage fromLabels(int width, int height, std::vector<uint8_t> labels);
  /// @brief A probability image with 8 channels; `probs` row-major, channel fastest.
  static SemanticImage fromProbabilities(int width, int height, std::vector<uint8_t> probs);
};

/// Magic word of the `.prob` header.
constexpr const char* kProbMagic = "mapfuse-prob";
/// Folder name of the semantics beside image_02.
constexpr const char* kSemanticsFolder = "semantics_02";

/// @brief `<drive>/semantics_02`.
std::filesystem::path semanticsDir(const std::filesystem::path& drive_dir);

/// @brief The semantics file of a frame (`<frame>.prob` if present, else `<frame>.png`),
/// nullopt when neither exists.
std::optional<std::filesystem::path> findSemanticImage(const std::filesystem::path& drive_dir,
                                                       const std::string& frame);

/// @brief Reads a `.png` label image or a `.prob` probability image (chosen by extension).
/// @throws IoError when unreadable; ParseError (file, field) for a bad header, size, channel
/// count, bit depth or a label outside 0..7.
SemanticImage readSemanticImage(const std::filesystem::path& path);
/// @brief The same from the bytes of a file; the extension of `file` chooses the kind and
/// `file` names it in errors.
SemanticImage parseSemanticImage(const std::string& bytes, const std::string& file);

/// @brief Writes a label image as `.png` or probabilities as `.prob` (by extension; the
/// image kind must match), atomically (temp file + rename).
/// @throws InputError for a kind/extension mismatch or inconsistent sizes; IoError on write.
void writeSemanticImage(const std::filesystem::path& path, const SemanticImage& image);

}  // namespace mapfuse::io
