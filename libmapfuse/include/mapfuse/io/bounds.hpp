#pragma once
/// @file The value ranges every mapfuse reader accepts (docs/formats.md "Value bounds"). A
/// value outside them is refused at read time with a ParseError naming the file, the field and
/// the bound, so that no stage ever sees a coordinate of 1e308 m, a count that wraps when
/// narrowed or a size whose product overflows. The bounds are physical, far beyond any real
/// drive, and small enough that the algorithms' arithmetic (grid keys, sample counts) stays
/// exact in 64 bits.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

namespace mapfuse::io::bounds {

/// Any metric coordinate or translation (ENU, odometry, body frame, m): |x|, |y|, |z| <= 1e7,
/// a quarter of the Earth's circumference from the origin.
constexpr double kMaxCoordinate = 1e7;
/// Ellipsoidal altitude (m), WGS84 fixes, origins and Lanelet2 `ele`: deepest trench to above
/// any aircraft.
constexpr double kMinAltitude = -1.2e4;
constexpr double kMaxAltitude = 1e5;
/// Timestamps (s): finite and |t| <= 1e10 (Unix time of the year 2286).
constexpr double kMaxStamp = 1e10;
/// Standard deviations (m or rad) and, squared, variances (m^2, rad^2).
constexpr double kMaxSigma = 1e6;
constexpr double kMaxVariance = kMaxSigma * kMaxSigma;
/// An LSM element's points in its anchor's body frame (m): within 1e4 m of the anchor, and its
/// polyline at most 1e4 m long (what a camera sees from one keyframe: tens of metres).
constexpr double kMaxElementRange = 1e4;
constexpr double kMaxElementLength = 1e4;
/// Consecutive keyframes of an LSM are at most kMaxKeyframeGap + kMaxSpeed * dt apart (m): a
/// keyframe farther away is a teleport, not a drive.
constexpr double kMaxKeyframeGap = 1e3;
/// Vertical extent of a pole or traffic light (m).
constexpr double kMaxElementHeight = 1e3;
/// Sensor-to-sensor and body-to-sensor translations of a calibration (m).
constexpr double kMaxExtrinsic = 1e3;
/// A LiDAR return, Velodyne frame (m).
constexpr double kMaxLidarRange = 1e4;
/// Image side (px) and pixel count of any image or calibrated camera.
constexpr int64_t kMaxImageSide = 65535;
constexpr int64_t kMaxImagePixels = int64_t(1) << 28;
/// Pixel coordinates of an observation (px): inside a generous frame around the image.
constexpr double kMaxPixel = 1e6;
/// Vehicle motion: speed (m/s), angular rate (rad/s), acceleration (m/s^2).
constexpr double kMaxSpeed = 1e3;
constexpr double kMaxAngularRate = 1e3;
constexpr double kMaxAcceleration = 1e4;
/// Attitude angles of an OXTS record (rad).
constexpr double kMaxAngle = 100.0;
/// JSON / CBOR nesting depth (objects and arrays); mapfuse documents need 6.
constexpr int kMaxNesting = 64;
/// Coordinate quantum of a compact vector map (m).
constexpr double kMinQuantum = 1e-9;
constexpr double kMaxQuantum = 1e3;
/// Total length (m) of one Bezier chain and of all chains of one document, which readers sample
/// every 0.5 m (at most 2e6 and 2e7 points).
constexpr double kMaxChainLength = 1e6;
constexpr double kMaxChainLengthPerDocument = 1e7;
/// OpenDRIVE (m): one road's length and every s along it; the sums over a map of road lengths,
/// of plan-view record lengths and of lane lengths (lanes are sampled every 0.5 m); lanes per
/// lane section; curvature of arcs and spirals (1/m; 1e3 is a 1 mm radius).
constexpr double kMaxOdrRoadLength = 1e5;
constexpr double kMaxOdrMapLength = 1e6;
constexpr int kMaxOdrLanesPerSection = 64;
constexpr double kMaxCurvature = 1e3;

/// @brief a * b when the product fits in int64 and both are non-negative, else nullopt.
inline std::optional<int64_t> checkedMultiply(int64_t a, int64_t b) {
  if (a < 0 || b < 0) return std::nullopt;
  if (a != 0 && b > std::numeric_limits<int64_t>::max() / a) return std::nullopt;
  return a * b;
}

/// @brief `lo <= v <= hi` for a finite v (false for NaN).
inline bool within(double v, double lo, double hi) {
  return v >= lo && v <= hi;
}

/// @brief A number for messages: up to 15 significant digits, no trailing zeros ("1e+07", "0.8").
std::string numberText(double v);
/// @brief "[lo, hi]" for messages, each as numberText.
std::string rangeText(double lo, double hi);

}  // namespace mapfuse::io::bounds
