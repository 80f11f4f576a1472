#include "mapfuse/io/semantic_image.hpp"

#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/bounds.hpp"
#include "mapfuse/io/png_decode.hpp"
#include "mapfuse/io/png_frames.hpp"

namespace mapfuse::io {
namespace fs = std::filesystem;
namespace {

void checkSizes(const SemanticImage& img, const std::string& what) {
  if (img.width <= 0 || img.height <= 0)
    throw InputError(what + ": semantic image size must be positive");
  const std::size_t per_pixel = img.isLabels() ? 1 : static_cast<std::size_t>(img.channels);
  if (img.data.size() != static_cast<std::size_t>(img.width) * img.height * per_pixel)
    throw InputError(what + ": semantic image data size does not match width*height*channels");
}

SemanticImage parseProb(const std::string& bytes, const std::string& file) {
  const auto eol = bytes.find('\n');
  if (eol == std::string::npos || eol > 200)
    throw ParseError(file, "header", "missing 'mapfuse-prob 1 <width> <height> <channels>' line");
  std::istringstream ss(bytes.substr(0, eol));
  std::string magic, extra;
  long version = 0, w = 0, h = 0, c = 0;
  if (!(ss >> magic) || magic != kProbMagic)
    throw ParseError(file, "header", "does not start with 'mapfuse-prob'");
  if (!(ss >> version) || version != 1) throw ParseError(file, "version", "unsupported (want 1)");
  const std::string side = " (1.." + std::to_string(bounds::kMaxImageSide) + " px)";
  if (!(ss >> w) || w <= 0 || w > bounds::kMaxImageSide)
    throw ParseError(file, "width", "missing or invalid" + side);
  if (!(ss >> h) || h <= 0 || h > bounds::kMaxImageSide)
    throw ParseError(file, "height", "missing or invalid" + side);
  if (int64_t(w) * h > bounds::kMaxImagePixels)
    throw ParseError(file, "height",
                     std::to_string(w) + "x" + std::to_string(h) + " px is more than " +
                         std::to_string(bounds::kMaxImagePixels) + " pixels");
  if (!(ss >> c)) throw ParseError(file, "channels", "missing or invalid");
  if (c != kNumLidarClasses)
    throw ParseError(file, "channels",
                     "is " + std::to_string(c) + ", must be " + std::to_string(kNumLidarClasses));
  if (ss >> extra) throw ParseError(file, "header", "unexpected text '" + extra + "'");
  const std::size_t expected = static_cast<std::size_t>(w) * h * c;
  const std::size_t have = bytes.size() - eol - 1;
  if (have != expected)
    throw ParseError(
        file, "data",
        "has " + std::to_string(have) + " bytes, header promises " + std::to_string(expected));
  SemanticImage img;
  img.width = static_cast<int>(w);
  img.height = static_cast<int>(h);
  img.channels = static_cast<int>(c);
  img.data.assign(bytes.begin() + static_cast<std::ptrdiff_t>(eol + 1), bytes.end());
  return img;
}

SemanticImage parseLabelPng(const std::string& bytes, const std::string& file) {
  const cv::Mat m = decodePng(bytes, file, cv::IMREAD_UNCHANGED);
  if (m.type() != CV_8UC1)
    throw ParseError(file, "png", "must be single-channel 8-bit (label ids 0..7)");
  SemanticImage img;
  img.width = m.cols;
  img.height = m.rows;
  img.data.resize(static_cast<std::size_t>(m.cols) * m.rows);
  for (int v = 0; v < m.rows; ++v) {
    const uint8_t* row = m.ptr<uint8_t>(v);
    for (int u = 0; u < m.cols; ++u) {
      if (row[u] >= kNumLidarClasses)
        throw ParseError(file, "label",
                         "pixel (" + std::to_string(u) + ", " + std::to_string(v) + ") has id " +
                             std::to_string(row[u]) + ", must be 0..7");
      img.data[static_cast<std::size_t>(v) * m.cols + u] = row[u];
    }
  }
  return img;
}

}  // namespace

SemanticImage SemanticImage::fromLabels(int width, int height, std::vector<uint8_t> labels) {
  SemanticImage img;
  img.width = width;
  img.height = height;
  img.data = std::move(labels);
  checkSizes(img, "fromLabels");
  return img;
}

SemanticImage SemanticImage::fromProbabilities(int width, int height, std::vector<uint8_t> probs) {
  SemanticImage img;
  img.width = width;
  img.height = height;
  img.channels = kNumLidarClasses;
  img.data = std::move(probs);
  checkSizes(img, "fromProbabilities");
  return img;
}

fs::path semanticsDir(const fs::path& drive_dir) {
  return drive_dir / kSemanticsFolder;
}

std::optional<fs::path> findSemanticImage(const fs::path& drive_dir, const std::string& frame) {
  const fs::path dir = semanticsDir(drive_dir);
  for (const char* ext : {".prob", ".png"}) {
    fs::path p = dir / (frame + ext);
    if (fs::is_regular_file(p)) return p;
  }
  return std::nullopt;
}

SemanticImage readSemanticImage(const fs::path& path) {
  const std::string ext = path.extension().string();
  if (ext != ".prob" && ext != ".png")
    throw IoError(path.string(), "unknown semantics extension (want .png or .prob)");
  return parseSemanticImage(readBytes(path), path.string());
}

SemanticImage parseSemanticImage(const std::string& bytes, const std::string& file) {
  const std::string ext = fs::path(file).extension().string();
  if (ext == ".prob") return parseProb(bytes, file);
  if (ext == ".png") return parseLabelPng(bytes, file);
  throw IoError(file, "unknown semantics extension (want .png or .prob)");
}

void writeSemanticImage(const fs::path& path, const SemanticImage& image) {
  checkSizes(image, path.string());
  const std::string ext = path.extension().string();
  if (ext == ".prob") {
    if (image.isLabels()) throw InputError(path.string() + ": .prob needs a probability image");
    const std::string header = std::string(kProbMagic) + " 1 " + std::to_string(image.width) + " " +
                               std::to_string(image.height) + " " + std::to_string(image.channels) +
                               "\n";
    writeFileAtomic(path, [&](std::ostream& out) {
      out.write(header.data(), static_cast<std::streamsize>(header.size()));
      out.write(reinterpret_cast<const char*>(image.data.data()),
                static_cast<std::streamsize>(image.data.size()));
    });
  } else if (ext == ".png") {
    if (!image.isLabels()) throw InputError(path.string() + ": .png needs a label image");
    for (uint8_t l : image.data)
      if (l >= kNumLidarClasses) throw InputError(path.string() + ": label id outside 0..7");
    const cv::Mat m(image.height, image.width, CV_8UC1, const_cast<uint8_t*>(image.data.data()));
    writePngFrame(path, m);
  } else {
    throw IoError(path.string(), "unknown semantics extension (want .png or .prob)");
  }
}

}  // namespace mapfuse::io
