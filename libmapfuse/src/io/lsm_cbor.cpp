#include "lsm_cbor.hpp"

#include "mapfuse/io/bounds.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <limits>

#include "mapfuse/io/lsm_io.hpp"
#include "utf8.hpp"

namespace mapfuse::io::detail {
namespace {

// ---------------------------------------------------------------- encoder (nlohmann's bytes)

class Writer {
 public:
  explicit Writer(std::size_t reserve) { out_.reserve(reserve); }
  std::string take() { return std::move(out_); }

  void head(uint8_t major, uint64_t n) {  // nlohmann's shortest form
    const uint8_t m = uint8_t(major << 5);
    if (n <= 0x17) {
      byte(m | uint8_t(n));
    } else if (n <= 0xff) {
      byte(m | 0x18);
      byte(uint8_t(n));
    } else if (n <= 0xffff) {
      byte(m | 0x19);
      big(n, 2);
    } else if (n <= 0xffffffffull) {
      byte(m | 0x1a);
      big(n, 4);
    } else {
      byte(m | 0x1b);
      big(n, 8);
    }
  }
  void integer(int64_t v) {
    if (v >= 0)
      head(0, uint64_t(v));
    else
      head(1, uint64_t(-1 - v));
  }
  void number(double v) {
    if (std::isnan(v)) {
      byte(0xf9), byte(0x7e), byte(0x00);
    } else if (std::isinf(v)) {
      byte(0xf9), byte(v > 0 ? 0x7c : 0xfc), byte(0x00);
    } else if (v >= double(std::numeric_limits<float>::lowest()) &&
               v <= double(std::numeric_limits<float>::max()) && double(float(v)) == v) {
      const float f = float(v);
      uint32_t bits;
      std::memcpy(&bits, &f, 4);
      byte(0xfa);
      big(bits, 4);
    } else {
      uint64_t bits;
      std::memcpy(&bits, &v, 8);
      byte(0xfb);
      big(bits, 8);
    }
  }
  void text(std::string_view s) {
    head(3, s.size());
    out_.append(s.data(), s.size());
  }
  void array(std::size_t n) { head(4, n); }
  void map(std::size_t n) { head(5, n); }
  void key(const char* k) { text(k); }
  void numbers(std::initializer_list<double> v) {
    array(v.size());
    for (double x : v) number(x);
  }

 private:
  void byte(uint8_t b) { out_.push_back(char(b)); }
  void big(uint64_t v, int bytes) {
    for (int i = bytes - 1; i >= 0; --i) byte(uint8_t(v >> (8 * i)));
  }
  std::string out_;
};

bool isDiagonal(const Matrix6d& C) {
  return (C - Matrix6d(C.diagonal().asDiagonal())).cwiseAbs().maxCoeff() == 0.0;
}

void writePose(Writer& w, const Pose3& T) {
  const Eigen::Quaterniond q(T.linear());
  w.map(2);
  w.key("q");
  w.numbers({q.w(), q.x(), q.y(), q.z()});
  w.key("t");
  w.numbers({T.translation().x(), T.translation().y(), T.translation().z()});
}

void writeOrigin(Writer& w, const geo::GeoOrigin& o) {
  w.map(3);
  w.key("alt"), w.number(o.alt);
  w.key("lat"), w.number(o.lat);
  w.key("lon"), w.number(o.lon);
}

void writeKeyframe(Writer& w, const Keyframe& k) {
  w.map(4);
  const bool diagonal = isDiagonal(k.covariance);
  if (!diagonal) {
    w.key("cov");
    w.array(21);
    for (int r = 0; r < 6; ++r)
      for (int c = r; c < 6; ++c) w.number(k.covariance(r, c));
  }
  w.key("id"), w.integer(k.id);
  w.key("pose"), writePose(w, k.T_frame_body);
  if (diagonal) {
    w.key("sigma");
    w.array(6);
    for (int i = 0; i < 6; ++i) w.number(std::sqrt(k.covariance(i, i)));
  }
  w.key("stamp"), w.number(k.stamp);
}

void writeElement(Writer& w, const Element& e) {
  const bool style = e.attributes.style != LineStyle::kNone;
  const bool color = e.attributes.color != LineColor::kNone;
  const bool height = e.height != 0.0, truth = e.truth_id >= 0;
  w.map(7 + style + color + height + truth);
  w.key("anchor"), w.integer(e.anchor);
  w.key("class"), w.text(crowdClassName(e.cls));
  if (color) w.key("color"), w.text(lineColorName(e.attributes.color));
  w.key("confidence"), w.number(e.confidence);
  w.key("cov");
  w.array(e.covariances.size());
  for (const auto& C : e.covariances)
    w.numbers({C(0, 0), C(0, 1), C(0, 2), C(1, 1), C(1, 2), C(2, 2)});
  if (height) w.key("height"), w.number(e.height);
  w.key("id"), w.integer(e.id);
  w.key("observations"), w.integer(e.observations);
  w.key("points");
  w.array(e.points_body.size());
  for (const auto& p : e.points_body) w.numbers({p.x(), p.y(), p.z()});
  if (style) w.key("style"), w.text(lineStyleName(e.attributes.style));
  if (truth) w.key("truth_id"), w.integer(e.truth_id);
}

// ---------------------------------------------------------------- decoder (fast path)

struct Fallback {};  // anything the general reader must judge

class Reader {
 public:
  explicit Reader(std::string_view b)
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

void require(bool ok) {
  if (!ok) throw Fallback{};
}

// The members of one object: `read(i)` reads the value of keys[i]. Each key at most once; any
// other key sends the file to the general reader. @return the keys present (bit i: keys[i]).
template <std::size_t N, class F>
Seen readMembers(Reader& r, const std::string_view (&keys)[N], F&& read) {
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

// Values beyond the readers' bounds go to the general reader, which refuses them with its own
// message (io/bounds.hpp: kMaxCoordinate for any metric coordinate, kMaxElementRange for
// body-frame element points; readLsm checks the others on the decoded LSM).
using bounds::kMaxCoordinate;
using bounds::kMaxElementRange;
bool within(const Eigen::Vector3d& v, double limit) {
  return v.cwiseAbs().maxCoeff() <= limit;
}

Pose3 readPose(Reader& r) {
  Eigen::Vector4d q;
  Eigen::Vector3d t;
  const Seen seen = readMembers(r, {"q", "t"}, [&](std::size_t i) {
    if (i == 0)
      q = r.fixed<4>();
    else
      t = r.fixed<3>();
  });
  require(seen.has(0) && seen.has(1) && std::abs(q.norm() - 1.0) <= 1e-3 &&
          within(t, kMaxCoordinate));
  Pose3 T = Pose3::Identity();
  T.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
  T.translation() = t;
  return T;
}

geo::GeoOrigin readOrigin(Reader& r) {
  geo::GeoOrigin o{};
  double* const value[] = {&o.lat, &o.lon, &o.alt};
  const Seen seen =
      readMembers(r, {"lat", "lon", "alt"}, [&](std::size_t i) { *value[i] = r.number(); });
  require(seen.has(0) && seen.has(1) && seen.has(2) && std::abs(o.lat) <= 90.0 &&
          std::abs(o.lon) <= 180.0);
  return o;
}

Keyframe readKeyframe(Reader& r) {
  Keyframe k;
  const Seen seen = readMembers(r, {"id", "stamp", "pose", "sigma", "cov"}, [&](std::size_t i) {
    if (i == 0) {
      k.id = r.integer();
    } else if (i == 1) {
      k.stamp = r.number();
    } else if (i == 2) {
      k.T_frame_body = readPose(r);
    } else if (i == 3) {
      const Vector6d s = r.fixed<6>();
      require(s.minCoeff() >= 0.0);
      k.covariance = s.cwiseAbs2().asDiagonal();
    } else {
      require(r.array() == 21);
      for (int a = 0; a < 6; ++a)
        for (int b = a; b < 6; ++b) k.covariance(a, b) = k.covariance(b, a) = r.number();
      require(k.covariance.diagonal().minCoeff() >= 0.0);
    }
  });
  require(seen.has(0) && seen.has(1) && seen.has(2) && seen.has(3) != seen.has(4));
  return k;
}

GpsFix readGps(Reader& r) {
  GpsFix g;
  double* const value[] = {&g.stamp,        &g.position.lat, &g.position.lon,
                           &g.position.alt, &g.sigma_h,      &g.sigma_v};
  const Seen seen = readMembers(r, {"stamp", "lat", "lon", "alt", "sigma_h", "sigma_v"},
                                [&](std::size_t i) { *value[i] = r.number(); });
  for (int i = 0; i < 6; ++i) require(seen.has(i));
  require(std::abs(g.position.lat) <= 90.0 && std::abs(g.position.lon) <= 180.0 &&
          g.sigma_h > 0.0 && g.sigma_v > 0.0);
  return g;
}

// PSD as io::readCov3 judges it (smallest eigenvalue >= -1e-9 max(1, |C|)); the eigen solver
// only when the leading minors do not already prove the matrix positive definite.
Eigen::Matrix3d readCov(Reader& r) {
  const Vector6d c = r.fixed<6>();
  Eigen::Matrix3d C;
  C << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
  const double m1 = C(0, 0), m2 = C(0, 0) * C(1, 1) - C(0, 1) * C(0, 1);
  if (!(m1 > 0 && m2 > 0 && C.determinant() > 0)) {
    const double min_eig =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C).eigenvalues().minCoeff();
    require(min_eig >= -1e-9 * std::max(1.0, C.norm()));
  }
  return C;
}

Element readElement(Reader& r) {
  Element e;
  // "sigma" instead of "cov" is not among the keys: rare, the general path reads it
  static constexpr std::string_view kKeys[] = {"id",           "class",  "style",   "color",
                                               "anchor",       "points", "cov",     "confidence",
                                               "observations", "height", "truth_id"};
  const Seen seen = readMembers(r, kKeys, [&](std::size_t i) {
    switch (i) {
      case 0: e.id = r.integer(); break;
      case 1: {
        const auto c = crowdClassFromName(std::string(r.text()));
        require(c.has_value());
        e.cls = *c;
        break;
      }
      case 2: {
        const auto s = lineStyleFromName(std::string(r.text()));
        require(s.has_value());
        e.attributes.style = *s;
        break;
      }
      case 3: {
        const auto c = lineColorFromName(std::string(r.text()));
        require(c.has_value());
        e.attributes.color = *c;
        break;
      }
      case 4: e.anchor = r.integer(); break;
      case 5:
        e.points_body.resize(r.array());
        for (auto& p : e.points_body) {
          p = r.fixed<3>();
          require(within(p, kMaxElementRange));
        }
        break;
      case 6:
        e.covariances.resize(r.array());
        for (auto& C : e.covariances) C = readCov(r);
        break;
      case 7: e.confidence = r.number(); break;
      case 8: {
        const int64_t o = r.integer();  // checked before narrowing to int
        require(o >= 1 && o <= std::numeric_limits<int>::max());
        e.observations = int(o);
        break;
      }
      case 9: e.height = r.number(); break;
      default: e.truth_id = r.integer();
    }
  });
  for (int i : {0, 1, 4, 5, 6, 7, 8}) require(seen.has(i));
  require(!e.points_body.empty() && e.covariances.size() == e.points_body.size() &&
          e.confidence >= 0.0 && e.confidence <= 1.0 && e.observations >= 1);
  return e;
}

}  // namespace

std::string encodeLsmCbor(const Lsm& lsm) {
  std::size_t points = 0;
  for (const auto& e : lsm.elements) points += e.points_body.size();
  Writer w(256 + 160 * lsm.keyframes.size() + 70 * lsm.gps.size() + 120 * lsm.elements.size() +
           85 * points);
  w.map(8 + (lsm.origin ? 1 : 0));
  w.key("drive_id"), w.text(lsm.drive_id);
  w.key("elements");
  w.array(lsm.elements.size());
  for (const auto& e : lsm.elements) writeElement(w, e);
  w.key("format"), w.text(kLsmFormat);
  w.key("frame"), w.text(lsm.frame == LsmFrame::kEnu ? "enu" : "odom");
  w.key("gps");
  w.array(lsm.gps.size());
  for (const auto& g : lsm.gps) {
    w.map(6);
    w.key("alt"), w.number(g.position.alt);
    w.key("lat"), w.number(g.position.lat);
    w.key("lon"), w.number(g.position.lon);
    w.key("sigma_h"), w.number(g.sigma_h);
    w.key("sigma_v"), w.number(g.sigma_v);
    w.key("stamp"), w.number(g.stamp);
  }
  w.key("keyframes");
  w.array(lsm.keyframes.size());
  for (const auto& k : lsm.keyframes) writeKeyframe(w, k);
  if (lsm.origin) w.key("origin"), writeOrigin(w, *lsm.origin);
  w.key("vehicle_id"), w.text(lsm.vehicle_id);
  w.key("version"), w.integer(kLsmVersion);
  return w.take();
}

std::optional<Lsm> decodeLsmCbor(std::string_view bytes) {
  try {
    Reader r(bytes);
    Lsm lsm;
    static constexpr std::string_view kKeys[] = {"format",     "version", "drive_id",
                                                 "vehicle_id", "frame",   "origin",
                                                 "keyframes",  "gps",     "elements"};
    const Seen seen = readMembers(r, kKeys, [&](std::size_t i) {
      switch (i) {
        case 0: require(r.text() == kLsmFormat); break;
        case 1: {
          const int64_t v = r.integer();
          require(v >= 1 && v <= kLsmVersion);
          break;
        }
        case 2: lsm.drive_id = std::string(r.text()); break;
        case 3: lsm.vehicle_id = std::string(r.text()); break;
        case 4: {
          const std::string_view f = r.text();
          require(f == "enu" || f == "odom");
          lsm.frame = f == "enu" ? LsmFrame::kEnu : LsmFrame::kOdom;
          break;
        }
        case 5: lsm.origin = readOrigin(r); break;
        case 6:
          lsm.keyframes.resize(r.array());
          for (auto& kf : lsm.keyframes) kf = readKeyframe(r);
          break;
        case 7:
          lsm.gps.resize(r.array());
          for (auto& g : lsm.gps) g = readGps(r);
          break;
        default:
          lsm.elements.resize(r.array());
          for (auto& e : lsm.elements) e = readElement(r);
      }
    });
    require(r.done());
    for (int i : {0, 1, 2, 4, 6, 8}) require(seen.has(i));
    require(lsm.frame != LsmFrame::kEnu || lsm.origin.has_value());
    return lsm;
  } catch (const Fallback&) {
    return std::nullopt;
  }
}

}  // namespace mapfuse::io::detail
