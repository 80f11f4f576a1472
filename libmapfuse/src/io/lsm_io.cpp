#include "mapfuse/io/lsm_io.hpp"

#include <algorithm>
#include <cmath>
#include "lsm_cbor.hpp"
#include "mapfuse/core/error.hpp"

#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/json_geometry.hpp"

namespace mapfuse::io {
namespace {

bool isDiagonal(const Matrix6d& C) {
  return (C - Matrix6d(C.diagonal().asDiagonal())).cwiseAbs().maxCoeff() == 0.0;
}

Json keyframeToJson(const Keyframe& k) {
  Json j = {{"id", k.id}, {"stamp", k.stamp}, {"pose", poseToJson(k.T_frame_body)}};
  if (isDiagonal(k.covariance)) {
    Json s = Json::array();
    for (int i = 0; i < 6; ++i) s.push_back(std::sqrt(k.covariance(i, i)));
    j["sigma"] = s;
  } else {
    Json c = Json::array();
    for (int r = 0; r < 6; ++r)
      for (int col = r; col < 6; ++col) c.push_back(k.covariance(r, col));
    j["cov"] = c;
  }
  return j;
}

Keyframe keyframeFromJson(const JsonView& v) {
  v.onlyKeys({"id", "stamp", "pose", "sigma", "cov"});
  Keyframe k;
  k.id = v.at("id").integer();
  k.stamp = v.at("stamp").number(-bounds::kMaxStamp, bounds::kMaxStamp);
  k.T_frame_body = readPose(v.at("pose"));
  if (auto s = v.find("sigma")) {
    s->vector(6);  // checks the count
    for (int i = 0; i < 6; ++i)
      k.covariance(i, i) = std::pow(s->at(std::size_t(i)).number(0.0, bounds::kMaxSigma), 2);
  } else if (auto c = v.find("cov")) {
    c->vector(21);  // checks the count
    int idx = 0;
    for (int r = 0; r < 6; ++r)
      for (int col = r; col < 6; ++col)
        k.covariance(r, col) = k.covariance(col, r) =
            c->at(std::size_t(idx++)).number(-bounds::kMaxVariance, bounds::kMaxVariance);
    if (k.covariance.diagonal().minCoeff() < 0.0) c->fail("negative variance on the diagonal");
  } else {
    v.at("sigma");  // throws "missing required field"
  }
  return k;
}

// A drive moves at most bounds::kMaxSpeed (plus kMaxKeyframeGap for lost data) between two
// keyframes: a keyframe farther from its predecessor is refused (a keyframe at 1e7 m in an
// otherwise 400 m drive went through georef with exit 0).
void checkStep(const Keyframe& prev, const Keyframe& k, const JsonView& v) {
  const double step = (k.T_frame_body.translation() - prev.T_frame_body.translation()).norm();
  const double dt = std::max(0.0, k.stamp - prev.stamp);
  if (step > bounds::kMaxKeyframeGap + bounds::kMaxSpeed * dt)
    v.at("pose").fail("keyframe is " + bounds::numberText(step) +
                      " m from the previous one after " + bounds::numberText(dt) +
                      " s (more than " + bounds::numberText(bounds::kMaxKeyframeGap) + " m + " +
                      bounds::numberText(bounds::kMaxSpeed) + " m/s)");
}

Json gpsToJson(const GpsFix& g) {
  return {{"stamp", g.stamp},      {"lat", g.position.lat}, {"lon", g.position.lon},
          {"alt", g.position.alt}, {"sigma_h", g.sigma_h},  {"sigma_v", g.sigma_v}};
}

GpsFix gpsFromJson(const JsonView& v) {
  v.onlyKeys({"stamp", "lat", "lon", "alt", "sigma_h", "sigma_v"});
  GpsFix g;
  g.stamp = v.at("stamp").number(-bounds::kMaxStamp, bounds::kMaxStamp);
  g.position = {v.at("lat").number(-90.0, 90.0), v.at("lon").number(-180.0, 180.0),
                v.at("alt").number(bounds::kMinAltitude, bounds::kMaxAltitude)};
  g.sigma_h = v.at("sigma_h").number(0.0, bounds::kMaxSigma);
  g.sigma_v = v.at("sigma_v").number(0.0, bounds::kMaxSigma);
  if (g.sigma_h <= 0.0) v.at("sigma_h").fail("must be positive");
  if (g.sigma_v <= 0.0) v.at("sigma_v").fail("must be positive");
  return g;
}

Json elementToJson(const Element& e) {
  Json j = {{"id", e.id},
            {"anchor", e.anchor},
            {"points", pointsToJson(e.points_body)},
            {"confidence", e.confidence},
            {"observations", e.observations}};
  writeClassAndAttributes(j, e.cls, e.attributes);
  Json cov = Json::array();
  for (const auto& C : e.covariances) cov.push_back(cov3ToJson(C));
  j["cov"] = cov;
  if (e.height != 0.0) j["height"] = e.height;
  if (e.truth_id >= 0) j["truth_id"] = e.truth_id;
  return j;
}

Element elementFromJson(const JsonView& v) {
  v.onlyKeys({"id", "class", "style", "color", "anchor", "points", "cov", "sigma", "confidence",
              "observations", "height", "truth_id"});
  Element e;
  e.id = v.at("id").integer();
  readClassAndAttributes(v, e.cls, e.attributes);
  e.anchor = v.at("anchor").integer();
  const JsonView points = v.at("points");
  for (std::size_t i = 0; i < points.size(); ++i)
    e.points_body.push_back(points.at(i).coordinate(bounds::kMaxElementRange));
  if (e.points_body.empty()) points.fail("an element needs at least one point");
  double length = 0.0;
  for (std::size_t i = 1; i < e.points_body.size(); ++i)
    length += (e.points_body[i] - e.points_body[i - 1]).norm();
  if (length > bounds::kMaxElementLength)
    points.fail("the element's polyline is " + bounds::numberText(length) + " m long, more than " +
                bounds::numberText(bounds::kMaxElementLength) + " m");
  if (auto cov = v.find("cov")) {
    if (cov->size() != e.points_body.size())
      cov->fail("expected one covariance per point (" + std::to_string(e.points_body.size()) +
                "), found " + std::to_string(cov->size()));
    for (std::size_t i = 0; i < cov->size(); ++i) e.covariances.push_back(readCov3(cov->at(i)));
  } else if (auto sig = v.find("sigma")) {
    if (sig->size() != e.points_body.size()) sig->fail("expected one sigma per point");
    for (std::size_t i = 0; i < sig->size(); ++i) {
      const double s = sig->at(i).number(0.0, bounds::kMaxSigma);
      e.covariances.push_back(Eigen::Matrix3d::Identity() * s * s);
    }
  } else {
    v.at("cov");  // throws "missing required field"
  }
  e.confidence = v.at("confidence").number();
  if (e.confidence < 0.0 || e.confidence > 1.0) v.at("confidence").fail("must be within [0, 1]");
  e.observations = v.at("observations").integerInt(1);
  if (auto h = v.find("height")) e.height = h->number(0.0, bounds::kMaxElementHeight);
  if (auto t = v.find("truth_id")) e.truth_id = t->integer();
  return e;
}

}  // namespace

Json lsmToJson(const Lsm& lsm) {
  Json j = {{"format", kLsmFormat},
            {"version", kLsmVersion},
            {"drive_id", lsm.drive_id},
            {"vehicle_id", lsm.vehicle_id},
            {"frame", lsm.frame == LsmFrame::kEnu ? "enu" : "odom"}};
  if (lsm.origin) j["origin"] = originToJson(*lsm.origin);
  Json kfs = Json::array(), gps = Json::array(), els = Json::array();
  for (const auto& k : lsm.keyframes) kfs.push_back(keyframeToJson(k));
  for (const auto& g : lsm.gps) gps.push_back(gpsToJson(g));
  for (const auto& e : lsm.elements) els.push_back(elementToJson(e));
  j["keyframes"] = std::move(kfs);
  j["gps"] = std::move(gps);
  j["elements"] = std::move(els);
  return j;
}

Lsm lsmFromJson(const Json& doc, const std::string& file) {
  const JsonView v(doc, file);
  v.onlyKeys({"format", "version", "drive_id", "vehicle_id", "frame", "origin", "keyframes", "gps",
              "elements"});
  v.checkFormat(kLsmFormat, kLsmVersion);
  Lsm lsm;
  lsm.drive_id = v.at("drive_id").string();
  if (auto vid = v.find("vehicle_id")) lsm.vehicle_id = vid->string();
  const std::string frame = v.at("frame").string();
  if (frame == "enu")
    lsm.frame = LsmFrame::kEnu;
  else if (frame != "odom")
    v.at("frame").fail("expected \"odom\" or \"enu\", found \"" + frame + "\"");
  if (auto o = v.find("origin"))
    lsm.origin = readOrigin(*o);
  else if (lsm.frame == LsmFrame::kEnu)
    v.at("origin");  // throws: enu requires an origin
  const JsonView kfs = v.at("keyframes");
  for (std::size_t i = 0; i < kfs.size(); ++i) {
    lsm.keyframes.push_back(keyframeFromJson(kfs.at(i)));
    if (i > 0) checkStep(lsm.keyframes[i - 1], lsm.keyframes[i], kfs.at(i));
  }
  if (auto gps = v.find("gps"))
    for (std::size_t i = 0; i < gps->size(); ++i) lsm.gps.push_back(gpsFromJson(gps->at(i)));
  const JsonView els = v.at("elements");
  for (std::size_t i = 0; i < els.size(); ++i) lsm.elements.push_back(elementFromJson(els.at(i)));
  validateLsm(lsm, file);
  return lsm;
}

namespace {

bool within(double x, double lo, double hi) {
  return x >= lo && x <= hi;
}

// The value bounds the general reader checks (docs/formats.md "Value bounds"), on an LSM the
// fast CBOR codec decoded: when one fails, the general reader reads the file again and refuses
// it naming the field, so both paths accept exactly the same files.
bool withinReaderBounds(const Lsm& lsm) {
  using namespace bounds;
  for (std::size_t i = 0; i < lsm.keyframes.size(); ++i) {
    const Keyframe& k = lsm.keyframes[i];
    if (!within(k.stamp, -kMaxStamp, kMaxStamp)) return false;
    if (!(k.covariance.cwiseAbs().maxCoeff() <= kMaxVariance)) return false;
    if (i > 0) {
      const Keyframe& prev = lsm.keyframes[i - 1];
      const double step = (k.T_frame_body.translation() - prev.T_frame_body.translation()).norm();
      if (!(step <= kMaxKeyframeGap + kMaxSpeed * std::max(0.0, k.stamp - prev.stamp)))
        return false;
    }
  }
  for (const GpsFix& g : lsm.gps)
    if (!within(g.stamp, -kMaxStamp, kMaxStamp) ||
        !within(g.position.alt, kMinAltitude, kMaxAltitude) || !within(g.sigma_h, 0, kMaxSigma) ||
        !within(g.sigma_v, 0, kMaxSigma) || g.sigma_h <= 0 || g.sigma_v <= 0)
      return false;
  for (const Element& e : lsm.elements) {
    double length = 0.0;
    for (std::size_t i = 0; i < e.points_body.size(); ++i) {
      if (!(e.points_body[i].cwiseAbs().maxCoeff() <= kMaxElementRange)) return false;
      if (i > 0) length += (e.points_body[i] - e.points_body[i - 1]).norm();
    }
    if (!(length <= kMaxElementLength) || !within(e.confidence, 0, 1) ||
        !within(e.height, 0, kMaxElementHeight))
      return false;
    for (const auto& c : e.covariances)
      if (!(c.cwiseAbs().maxCoeff() <= kMaxVariance)) return false;
  }
  return true;
}

}  // namespace

Lsm readLsm(const std::filesystem::path& path) {
  // CBOR: the fast codec (lsm_cbor.hpp); whatever it declines, or whatever lies outside the
  // readers' bounds, the general path judges.
  if (encodingOf(path) == Encoding::kCbor) {
    const std::string bytes = readBytes(path);
    std::optional<Lsm> lsm = detail::decodeLsmCbor(bytes);
    if (lsm && withinReaderBounds(*lsm)) {
      validateLsm(*lsm, path.string());
      return std::move(*lsm);
    }
  }
  return lsmFromJson(readDocument(path), path.string());
}

void writeLsm(const std::filesystem::path& path, const Lsm& lsm) {
  if (encodingOf(path) == Encoding::kCbor)
    writeBytesAtomic(path, detail::encodeLsmCbor(lsm));  // the bytes of to_cbor(lsmToJson(lsm))
  else
    writeDocument(path, lsmToJson(lsm));
}

}  // namespace mapfuse::io
