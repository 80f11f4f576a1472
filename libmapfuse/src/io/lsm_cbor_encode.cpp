// The CBOR encoder of LSM files (lsm_cbor.hpp): byte for byte what nlohmann's to_cbor writes.
#include "lsm_cbor.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <limits>

#include "mapfuse/io/lsm_io.hpp"

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

}  // namespace mapfuse::io::detail
