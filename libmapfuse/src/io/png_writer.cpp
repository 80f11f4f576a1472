#include "mapfuse/io/png_writer.hpp"

#include <zlib.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"

namespace mapfuse::io {

namespace {

void put32(std::string& out, uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<char>((v >> s) & 0xff));
}

void chunk(std::string& out, const char* type, const std::string& data) {
  put32(out, static_cast<uint32_t>(data.size()));
  const std::size_t start = out.size();
  out.append(type, 4);
  out += data;
  const auto* bytes = reinterpret_cast<const Bytef*>(out.data() + start);
  put32(out, static_cast<uint32_t>(crc32(0L, bytes, static_cast<uInt>(out.size() - start))));
}

int paeth(int a, int b, int c) {
  const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

}  // namespace

std::string encodePng(const cv::Mat& image) {
  if (image.empty()) throw InputError("PNG encoding: empty image");
  const int channels = image.channels();
  if (image.depth() != CV_8U || (channels != 1 && channels != 3 && channels != 4))
    throw InputError("PNG encoding: 8-bit images with 1, 3 or 4 channels only");
  const int w = image.cols, h = image.rows, stride = w * channels;
  // Rows in PNG channel order (RGB / RGBA), each behind its filter-type byte.
  std::vector<uint8_t> raw(static_cast<std::size_t>(h) * (stride + 1));
  std::vector<uint8_t> prev(stride, 0), cur(stride);
  std::array<std::vector<uint8_t>, 5> cand;
  for (auto& c : cand) c.resize(stride);
  for (int y = 0; y < h; ++y) {
    const uint8_t* src = image.ptr<uint8_t>(y);
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < channels; ++k) {
        const int from = channels >= 3 && k < 3 ? 2 - k : k;  // BGR(A) -> RGB(A)
        cur[x * channels + k] = src[x * channels + from];
      }
    long best_cost = -1;
    int best = 0;
    for (int f = 0; f < 5; ++f) {
      long cost = 0;
      for (int i = 0; i < stride; ++i) {
        const int a = i >= channels ? cur[i - channels] : 0, b = prev[i];
        const int c = i >= channels ? prev[i - channels] : 0;
        const int pred = f == 0   ? 0
                         : f == 1 ? a
                         : f == 2 ? b
                         : f == 3 ? (a + b) / 2
                                  : paeth(a, b, c);
        const auto v = static_cast<uint8_t>(cur[i] - pred);
        cand[f][i] = v;
        cost += v < 128 ? v : 256 - v;
      }
      if (best_cost < 0 || cost < best_cost) best_cost = cost, best = f;
    }
    uint8_t* row = raw.data() + static_cast<std::size_t>(y) * (stride + 1);
    row[0] = static_cast<uint8_t>(best);
    std::copy(cand[best].begin(), cand[best].end(), row + 1);
    std::swap(prev, cur);
  }
  uLongf packed_size = compressBound(static_cast<uLong>(raw.size()));
  std::string packed(packed_size, '\0');
  if (compress2(reinterpret_cast<Bytef*>(packed.data()), &packed_size, raw.data(),
                static_cast<uLong>(raw.size()), 6) != Z_OK)
    throw IoError("PNG encoding", "deflate failed");
  packed.resize(packed_size);

  std::string out("\x89PNG\r\n\x1a\n", 8);
  std::string ihdr;
  put32(ihdr, static_cast<uint32_t>(w));
  put32(ihdr, static_cast<uint32_t>(h));
  ihdr.push_back(8);                                                             // bit depth
  ihdr.push_back(static_cast<char>(channels == 1 ? 0 : channels == 3 ? 2 : 6));  // colour type
  ihdr.append(3, '\0');  // deflate, adaptive filtering, no interlace
  chunk(out, "IHDR", ihdr);
  chunk(out, "IDAT", packed);
  chunk(out, "IEND", "");
  return out;
}

void writePng(const std::filesystem::path& path, const cv::Mat& image) {
  writeBytesAtomic(path, encodePng(image));
}

}  // namespace mapfuse::io
