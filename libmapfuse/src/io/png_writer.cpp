#include "mapfuse/io/png_writer.hpp"

#include <zlib.h>

#include <algorithm>
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

// The five PNG filter types (none, sub, up, average, paeth) of one row, each in its own loop.
void filterCandidates(const std::vector<uint8_t>& cur, const std::vector<uint8_t>& prev, int bpp,
                      std::array<std::vector<uint8_t>, 5>& cand) {
  const int n = int(cur.size());
  for (int i = 0; i < n; ++i) cand[0][i] = cur[i];
  for (int i = 0; i < n; ++i) cand[1][i] = uint8_t(cur[i] - (i >= bpp ? cur[i - bpp] : 0));
  for (int i = 0; i < n; ++i) cand[2][i] = uint8_t(cur[i] - prev[i]);
  for (int i = 0; i < n; ++i)
    cand[3][i] = uint8_t(cur[i] - ((i >= bpp ? cur[i - bpp] : 0) + prev[i]) / 2);
  for (int i = 0; i < n; ++i)
    cand[4][i] = uint8_t(
        cur[i] - (i >= bpp ? paeth(cur[i - bpp], prev[i], prev[i - bpp]) : paeth(0, prev[i], 0)));
}

}  // namespace

std::string encodePng(const cv::Mat& image) {
  if (image.empty()) throw InputError("PNG encoding: empty image");
  const int channels = image.channels();
  if (image.depth() != CV_8U || (channels != 1 && channels != 3 && channels != 4))
    throw InputError("PNG encoding: 8-bit images with 1, 3 or 4 channels only");
  const int w = image.cols, h = image.rows, stride = w * channels;
  // Rows in PNG channel order (RGB / RGBA), each behind its filter-type byte, streamed through
  // deflate a row at a time (no whole-image buffers: a map PNG is megabytes raw, kilobytes packed).
  z_stream z{};
  if (deflateInit(&z, 6) != Z_OK) throw IoError("PNG encoding", "deflate init failed");
  std::string packed;
  std::array<Bytef, 1 << 16> buf;
  auto feed = [&](const uint8_t* data, std::size_t n, int flush) {
    z.next_in = const_cast<Bytef*>(data);
    z.avail_in = static_cast<uInt>(n);
    do {
      z.next_out = buf.data();
      z.avail_out = static_cast<uInt>(buf.size());
      const int rc = deflate(&z, flush);
      if (rc == Z_STREAM_ERROR) {
        deflateEnd(&z);
        throw IoError("PNG encoding", "deflate failed");
      }
      packed.append(reinterpret_cast<const char*>(buf.data()), buf.size() - z.avail_out);
    } while (z.avail_out == 0 || (flush == Z_FINISH && z.avail_in > 0));
  };
  std::vector<uint8_t> prev(stride, 0), cur(stride), row(stride + 1);
  std::array<std::vector<uint8_t>, 5> cand;
  for (auto& c : cand) c.resize(stride);
  for (int y = 0; y < h; ++y) {
    const uint8_t* src = image.ptr<uint8_t>(y);
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < channels; ++k) {
        const int from = channels >= 3 && k < 3 ? 2 - k : k;  // BGR(A) -> RGB(A)
        cur[x * channels + k] = src[x * channels + from];
      }
    if (y > 0 && std::equal(cur.begin(), cur.end(), prev.begin())) {
      row[0] = 2;  // "Up" on a repeated row (most of a map's background): all zero, no search
      std::fill(row.begin() + 1, row.end(), uint8_t(0));
    } else {
      filterCandidates(cur, prev, channels, cand);
      long best_cost = -1;
      int best = 0;
      for (int f = 0; f < 5; ++f) {
        long cost = 0;
        for (const uint8_t v : cand[f]) cost += v < 128 ? v : 256 - v;
        if (best_cost < 0 || cost < best_cost) best_cost = cost, best = f;
      }
      row[0] = static_cast<uint8_t>(best);
      std::copy(cand[best].begin(), cand[best].end(), row.begin() + 1);
    }
    feed(row.data(), row.size(), Z_NO_FLUSH);
    std::swap(prev, cur);
  }
  feed(nullptr, 0, Z_FINISH);
  deflateEnd(&z);

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
