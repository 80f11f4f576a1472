#pragma once
/// @file The CBOR reader of the fast LSM decoder (private to libmapfuse/src/io; lsm_cbor.hpp):
/// definite-length items of the types an LSM holds; anything else throws Fallback, which sends
/// the file to the general reader.
#include <cstdint>
#include <cstring>
#include <limits>
#include <string_view>

#include "utf8.hpp"

namespace mapfuse::io::detail {

struct Fallback {};  // anything the general reader must judge

class CborReader {
 public:
  explicit CborReader(std::string_view b)
      : p_(reinterpret_cast<const uint8_t*>(b.data())), end_(p_ + b.size()) {}
  bool done() const { return p_ == end_; }

  uint8_t peek() const {
    if (p_ >= end_) throw Fallback{};
    return *p_;
  }
  // Major type and argument of the next item (definite lengths and plain integers only).
  uint64_t head(uint8_t major) {
    const uint8_t b = peek();
    if ((b >> 5) != major) throw Fallback{};
    ++p_;
    const uint8_t ai = b & 31;
    if (ai < 24) return ai;
    const int n = ai == 24 ? 1 : ai == 25 ? 2 : ai == 26 ? 4 : ai == 27 ? 8 : 0;
    if (n == 0 || end_ - p_ < n) throw Fallback{};
    uint64_t v = 0;
    for (int i = 0; i < n; ++i) v = (v << 8) | *p_++;
    return v;
  }
  std::size_t array() { return std::size_t(checkCount(head(4))); }
  std::size_t map() { return std::size_t(checkCount(head(5))); }
  std::string_view text() {
    const uint64_t n = head(3);
    if (uint64_t(end_ - p_) < n) throw Fallback{};
    const std::string_view s(reinterpret_cast<const char*>(p_), n);
    if (!validUtf8(s)) throw Fallback{};  // the generic reader names the problem
    p_ += n;
    return s;
  }
  // A finite number (integer or float), as JsonView::number.
  double number() {
    const uint8_t b = peek();
    const uint8_t major = b >> 5;
    double v;
    if (major == 0) {
      v = double(head(0));
    } else if (major == 1) {
      v = -1.0 - double(head(1));
    } else if (b == 0xfa) {
      ++p_;
      v = double(bitsAs<float, uint32_t>(4));
    } else if (b == 0xfb) {
      ++p_;
      v = bitsAs<double, uint64_t>(8);
    } else {
      throw Fallback{};
    }
    if (!std::isfinite(v)) throw Fallback{};
    return v;
  }
  // An integer, as JsonView::integer (integral floats below 9e15 too).
  int64_t integer() {
    const uint8_t major = peek() >> 5;
    if (major == 0) {
      const uint64_t u = head(0);
      if (u > uint64_t(std::numeric_limits<int64_t>::max())) throw Fallback{};
      return int64_t(u);
    }
    if (major == 1) {
      const uint64_t u = head(1);
      if (u > uint64_t(std::numeric_limits<int64_t>::max())) throw Fallback{};
      return -1 - int64_t(u);
    }
    const double v = number();
    if (v != std::floor(v) || std::abs(v) >= 9e15) throw Fallback{};
    return int64_t(v);
  }
  template <int N>
  Eigen::Matrix<double, N, 1> fixed() {
    if (array() != N) throw Fallback{};
    Eigen::Matrix<double, N, 1> v;
    for (int i = 0; i < N; ++i) v[i] = number();
    return v;
  }

 private:
  uint64_t checkCount(uint64_t n) const {
    if (n > uint64_t(end_ - p_)) throw Fallback{};  // every item takes at least one byte
    return n;
  }
  template <class F, class U>
  F bitsAs(int n) {
    if (end_ - p_ < n) throw Fallback{};
    U u = 0;
    for (int i = 0; i < n; ++i) u = (u << 8) | *p_++;
    F f;
    std::memcpy(&f, &u, sizeof(F));
    return f;
  }
  const uint8_t* p_;
  const uint8_t* end_;
};

// Each key of an object at most once.
class Seen {
 public:
  void mark(int bit) {
    if (bits_ & (1u << bit)) throw Fallback{};
    bits_ |= 1u << bit;
  }
  bool has(int bit) const { return bits_ & (1u << bit); }

 private:
  uint32_t bits_ = 0;
};

inline void require(bool ok) {
  if (!ok) throw Fallback{};
}

// The members of one object: `read(i)` reads the value of keys[i]. Each key at most once; any
// other key sends the file to the general reader. @return the keys present (bit i: keys[i]).
template <std::size_t N, class F>
Seen readMembers(CborReader& r, const std::string_view (&keys)[N], F&& read) {
  Seen seen;
  for (std::size_t n = r.map(); n > 0; --n) {
    const std::string_view k = r.text();
    std::size_t i = 0;
    while (i < N && k != keys[i]) ++i;
    if (i == N) throw Fallback{};
    seen.mark(static_cast<int>(i));
    read(i);
  }
  return seen;
}

}  // namespace mapfuse::io::detail
