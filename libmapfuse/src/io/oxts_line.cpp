#include "mapfuse/io/oxts_line.hpp"

#include <cmath>
#include <sstream>
#include <vector>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/bounds.hpp"

namespace mapfuse::io {
namespace {
const char* const kFieldNames[30] = {
    "lat",          "lon",     "alt",     "roll",    "pitch",   "yaw",    "vn", "ve",
    "vf",           "vl",      "vu",      "ax",      "ay",      "az",     "af", "al",
    "au",           "wx",      "wy",      "wz",      "wf",      "wl",     "wu", "pos_accuracy",
    "vel_accuracy", "navstat", "numsats", "posmode", "velmode", "orimode"};
}  // namespace

geo::OxtsRecord parseOxtsLine(const std::string& line, const std::string& file) {
  std::istringstream ss(line);
  std::vector<double> v;
  std::string token;
  while (ss >> token) {
    if (v.size() == 30) throw ParseError(file, "", "more than 30 OXTS fields");
    try {
      std::size_t used = 0;
      const double x = std::stod(token, &used);
      if (used != token.size()) throw std::invalid_argument(token);
      v.push_back(x);
    } catch (const std::exception&) {
      throw ParseError(file, kFieldNames[v.size()], "not a number: '" + token + "'");
    }
    if (!std::isfinite(v.back())) throw ParseError(file, kFieldNames[v.size() - 1], "not finite");
  }
  if (v.size() < 30)
    throw ParseError(file, kFieldNames[v.size()],
                     "missing (found " + std::to_string(v.size()) + " of 30 OXTS fields)");
  // Ranges (docs/formats.md "Value bounds"): checked before use, and the five status fields
  // are small integers checked before the conversion to int.
  auto limit = [&](int k, double lo, double hi) {
    if (!(v[k] >= lo && v[k] <= hi))
      throw ParseError(
          file, kFieldNames[k],
          bounds::numberText(v[k]) + " is outside " + bounds::rangeText(lo, hi));
  };
  limit(0, -85.0,
        85.0);  // the devkit's Mercator pose (oxtsToMercatorPose) is infinite at the poles
  limit(1, -180.0, 180.0);
  limit(2, bounds::kMinAltitude, bounds::kMaxAltitude);
  for (int k = 3; k <= 5; ++k) limit(k, -bounds::kMaxAngle, bounds::kMaxAngle);
  for (int k = 6; k <= 10; ++k) limit(k, -bounds::kMaxSpeed, bounds::kMaxSpeed);
  for (int k = 11; k <= 16; ++k)
    limit(k, -bounds::kMaxAcceleration, bounds::kMaxAcceleration);
  for (int k = 17; k <= 22; ++k)
    limit(k, -bounds::kMaxAngularRate, bounds::kMaxAngularRate);
  limit(23, 0.0, bounds::kMaxSigma);
  limit(24, 0.0, bounds::kMaxSigma);
  for (int k = 25; k < 30; ++k) {
    limit(k, -1e6, 1e6);
    if (v[k] != std::floor(v[k])) throw ParseError(file, kFieldNames[k], "not an integer");
  }
  auto i = [&](int k) { return static_cast<int>(v[k]); };
  return geo::OxtsRecord{v[0],  v[1],  v[2],  v[3],  v[4],  v[5],  v[6],  v[7],  v[8],  v[9],
                    v[10], v[11], v[12], v[13], v[14], v[15], v[16], v[17], v[18], v[19],
                    v[20], v[21], v[22], v[23], v[24], i(25), i(26), i(27), i(28), i(29)};
}

}  // namespace mapfuse::io
