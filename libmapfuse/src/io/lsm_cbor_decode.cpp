// The fast CBOR decoder of LSM files (lsm_cbor.hpp): straight from the bytes to the structs,
// Fallback (nullopt) for anything the general reader must judge.
#include "lsm_cbor.hpp"

#include "mapfuse/io/bounds.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <limits>

#include "lsm_cbor_reader.hpp"
#include "mapfuse/io/lsm_io.hpp"

namespace mapfuse::io::detail {
namespace {

// Values beyond the readers' bounds go to the general reader, which refuses them with its own
// message (io/bounds.hpp: kMaxCoordinate for any metric coordinate, kMaxElementRange for
// body-frame element points; readLsm checks the others on the decoded LSM).
using bounds::kMaxCoordinate;
using bounds::kMaxElementRange;
bool within(const Eigen::Vector3d& v, double limit) {
  return v.cwiseAbs().maxCoeff() <= limit;
}

Pose3 readPose(CborReader& r) {
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

geo::GeoOrigin readOrigin(CborReader& r) {
  geo::GeoOrigin o{};
  double* const value[] = {&o.lat, &o.lon, &o.alt};
  const Seen seen =
      readMembers(r, {"lat", "lon", "alt"}, [&](std::size_t i) { *value[i] = r.number(); });
  require(seen.has(0) && seen.has(1) && seen.has(2) && std::abs(o.lat) <= 90.0 &&
          std::abs(o.lon) <= 180.0);
  return o;
}

Keyframe readKeyframe(CborReader& r) {
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

GpsFix readGps(CborReader& r) {
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
Eigen::Matrix3d readCov(CborReader& r) {
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

Element readElement(CborReader& r) {
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

std::optional<Lsm> decodeLsmCbor(std::string_view bytes) {
  try {
    CborReader r(bytes);
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
