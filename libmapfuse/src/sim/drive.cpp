#include "mapfuse/sim/drive.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "draw_order.hpp"
#include "mapfuse/core/angles.hpp"
#include "mapfuse/core/error.hpp"

namespace mapfuse::sim {

namespace {
constexpr double kGravity = 9.80665;  // m/s^2
constexpr double kPathStep = 0.5;     // m, route resampling
constexpr int kSmoothHalfWindow = 4;  // samples (2 m) of the path smoothing
constexpr int kSmoothPasses = 3;
constexpr int kRouteAttempts = 20;
// A route ends at most this far past its target length: the last lane appended is cut there,
// so that one very long lanelet (a map of a motorway, or a fuzzed node 700 km away) cannot make
// a drive of hours (a drive holds ~0.4 kB per IMU sample). Lanes of street maps are far shorter,
// so their routes are not cut.
constexpr double kMaxRouteOvershoot = 1000.0;  // m

/// The first `length` metres of `line` (the line itself when it is not longer).
Polyline headOf(const Polyline& line, double length) {
  const auto cum = arcLengths(line);
  if (cum.back() <= length) return line;
  Polyline out;
  for (std::size_t i = 0; i < line.size() && cum[i] < length; ++i) out.push_back(line[i]);
  out.push_back(pointAt(line, cum, length));
  return out;
}
/// Of `candidates`, the lane whose end lies farthest (horizontally) from `start`.
std::size_t farthestFrom(const World& world, const std::vector<std::size_t>& candidates,
                         const Eigen::Vector3d& start) {
  std::size_t best = candidates.front();
  double best_d = -1.0;
  for (std::size_t c : candidates) {
    const double d = (world.lanes[c].centerline.back() - start).head<2>().norm();
    if (d > best_d) best = c, best_d = d;
  }
  return best;
}
/// Heading of the path at each vertex (central difference), unwrapped.
std::vector<double> unwrappedHeadings(const Polyline& path) {
  std::vector<double> heading(path.size());
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Eigen::Vector3d t = path[std::min(path.size() - 1, i + 1)] - path[i > 0 ? i - 1 : 0];
    heading[i] = std::atan2(t.y(), t.x());
    if (i > 0) heading[i] = heading[i - 1] + std::remainder(heading[i] - heading[i - 1], 2 * kPi);
  }
  return heading;
}
/// The body sits on the road: nose up by the path's grade at each vertex (pitch = -asin(dz/ds),
/// the body x axis of poseFromXyzRpy is (cos p cos y, cos p sin y, -sin p)).
std::vector<double> gradePitch(const Polyline& path, const std::vector<double>& cum) {
  std::vector<double> pitch(path.size(), 0.0);
  for (std::size_t i = 0; i < path.size(); ++i) {
    const std::size_t a = i > 0 ? i - 1 : 0, b = std::min(path.size() - 1, i + 1);
    const double ds = cum[b] - cum[a];
    if (ds > 0) pitch[i] = -std::asin(std::clamp((path[b].z() - path[a].z()) / ds, -1.0, 1.0));
  }
  return pitch;
}
/// The body sits on the road across, too: it rolls by the surface's cross-slope under each vertex,
/// measured over ±kBankHalfSpan to either side (roll > 0: left side up, poseFromXyzRpy's body y
/// axis is (.., .., sin roll) for a level heading). Without a surface every roll is 0.
constexpr double kBankHalfSpan = 1.0;  // m, about the half-track of a car
std::vector<double> bankRoll(const Polyline& path, const std::vector<double>& heading,
                             const std::function<double(const Eigen::Vector3d&)>& surface) {
  std::vector<double> roll(path.size(), 0.0);
  if (!surface) return roll;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Eigen::Vector3d left(-std::sin(heading[i]), std::cos(heading[i]), 0.0);
    const Eigen::Vector3d& p = path[i];
    roll[i] = std::atan((surface(p + kBankHalfSpan * left) - surface(p - kBankHalfSpan * left)) /
                        (2.0 * kBankHalfSpan));
  }
  return roll;
}
/// An IMU mounted pitched by `pitch` against the body reads gyro and accel in its own frame.
void mountImu(std::vector<ImuRecord>& imu, double pitch) {
  if (pitch == 0.0) return;
  const Eigen::Matrix3d R_imu_body =
      Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()).toRotationMatrix().transpose();
  for (auto& r : imu) r.gyro = R_imu_body * r.gyro, r.accel = R_imu_body * r.accel;
}
}  // namespace

bool DriveParams::dividesImuRate(double rate) const {
  const double ratio = imu_rate / rate;
  return rate > 0.0 && rate <= imu_rate && std::abs(ratio - std::round(ratio)) < 1e-9;
}

uint64_t deriveSeed(uint64_t base, uint64_t index) {
  uint64_t z = base + 0x9E3779B97F4A7C15ull * (index + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

std::vector<Polyline> planRoutes(const World& world, int count, double length, uint64_t seed,
                                 bool outward) {
  std::mt19937_64 rng(seed);
  std::vector<Polyline> routes;
  if (world.lanes.empty()) return routes;
  std::uniform_int_distribution<std::size_t> pick(0, world.lanes.size() - 1);
  for (int r = 0; r < count; ++r) {
    Polyline best;
    double best_len = -1.0;
    for (int attempt = 0; attempt < kRouteAttempts; ++attempt) {
      std::size_t lane = pick(rng);
      Polyline route;
      std::vector<int> visits(world.lanes.size(), 0);
      while (true) {
        const auto& c = world.lanes[lane].centerline;
        route.insert(route.end(), c.begin() + (route.empty() ? 0 : 1), c.end());
        ++visits[lane];
        if (polylineLength(route) >= length) break;
        // Prefer lanes not yet driven on this route.
        std::vector<std::size_t> next;
        for (std::size_t s : world.lanes[lane].successors)
          if (visits[s] == 0) next.push_back(s);
        if (next.empty()) next = world.lanes[lane].successors;
        if (next.empty()) break;
        if (outward) {
          const std::size_t to = farthestFrom(world, next, route.front());
          // the route ends where every way on leads back towards its start
          if (visits[to] > 0 ||
              (world.lanes[to].centerline.back() - route.front()).head<2>().norm() <
                  (route.back() - route.front()).head<2>().norm())
            break;
          lane = to;
          continue;
        }
        lane = next[std::uniform_int_distribution<std::size_t>(0, next.size() - 1)(rng)];
        if (visits[lane] > 1) break;
      }
      route = headOf(route, length + kMaxRouteOvershoot);
      const double len = polylineLength(route);
      if (len > best_len) best = route, best_len = len;
      if (len >= (outward ? length : 0.5 * length)) break;  // outward: the longest of the tries
    }
    routes.push_back(best);
  }
  return routes;
}

namespace {

/// IMU samples of the true trajectory: gyro from consecutive rotations, accel from second
/// differences (specific force), each with its noise; the gyro's bias of the drive added.
void synthesizeImu(Drive& d, const DriveParams& P, std::normal_distribution<double>& N01,
                   std::mt19937_64& rng) {
  const int n = int(d.truth.size());
  const double dt = 1.0 / P.imu_rate;
  constexpr int kAccelStride = 25;  // samples, 0.25 s at 100 Hz
  d.imu.resize(n);
  const double gyro_sigma = P.gyro_noise_density * std::sqrt(P.imu_rate);
  for (int k = 0; k < n; ++k) {
    const int k1 = std::min(n - 1, k + 1);
    Eigen::Vector3d omega = Eigen::Vector3d::Zero();
    if (k1 > k) {
      const Eigen::AngleAxisd aa(d.truth[k].linear().transpose() * d.truth[k1].linear());
      omega = aa.angle() * aa.axis() / dt;
    }
    // The route is a polyline: a second difference over one sample puts a turn's whole change of
    // direction into the samples at its vertices (spikes of tens of m/s^2, none in between). Over
    // +-kAccelStride samples it is the acceleration averaged across the vertices, as a car that
    // turns smoothly feels it.
    const int a1 = std::min(n - 1, k + kAccelStride), a0 = std::max(0, k - kAccelStride);
    const int h = std::min(a1 - k, k - a0);
    Eigen::Vector3d acc = Eigen::Vector3d::Zero();
    if (h > 0)
      acc = (d.truth[k + h].translation() - 2 * d.truth[k].translation() +
             d.truth[k - h].translation()) /
            (h * h * dt * dt);
    d.imu[k].stamp = d.stamps[k];
    d.imu[k].gyro = omega + d.gyro_bias + gyro_sigma * drawVector3(N01, rng);
    d.imu[k].accel = d.truth[k].linear().transpose() * (acc + Eigen::Vector3d(0, 0, kGravity)) +
                     P.accel_noise * drawVector3(N01, rng);
  }
}

/// Wheel speeds at the wheel rate, with the drive's scale error and noise.
void synthesizeWheel(Drive& d, const DriveParams& P, std::normal_distribution<double>& N01,
                     std::mt19937_64& rng) {
  const int n = int(d.truth.size());
  const double dt = 1.0 / P.imu_rate;
  // Wheel speed at the wheel rate: the body's own speed along its x axis (central difference of
  // the true positions). In a turn the body, a lane off the route's centre line, moves faster or
  // slower than d.speed (by omega times the offset); a wheel measures the body's speed.
  const int wheel_every = std::max(1, static_cast<int>(std::lround(P.imu_rate / P.wheel_rate)));
  for (int k = 0; k < n; k += wheel_every) {
    const int k1 = std::min(n - 1, k + 1), k0 = std::max(0, k - 1);
    const double speed = k1 > k0 ? (d.truth[k].linear().transpose() *
                                    (d.truth[k1].translation() - d.truth[k0].translation()))
                                           .x() /
                                       ((k1 - k0) * dt)
                                 : d.speed;
    d.wheel.push_back(
        {d.stamps[k], (1.0 + d.wheel_scale_error) * speed + P.wheel_speed_noise * N01(rng)});
  }
}

}  // namespace

Drive simulateDrive(const Polyline& route, const DriveParams& P, const geo::EnuConverter& enu,
                    uint64_t seed, const std::function<double(const Eigen::Vector3d&)>& surface) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> N01(0.0, 1.0);
  auto U = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  Drive d;
  // Path: resampled, smoothed, with headings at the vertices (unwrapped).
  const Polyline path = smooth(resample(route, kPathStep), kSmoothHalfWindow, kSmoothPasses);
  // A route collapsed to a point (degenerate map geometry) has nothing to drive.
  if (path.size() < 2) throw InputError("the route has no length (its lanes collapse to a point)");
  const auto cum = arcLengths(path);
  const double L = cum.back();
  const std::vector<double> heading = unwrappedHeadings(path);
  const std::vector<double> grade_pitch = gradePitch(path, cum);
  const std::vector<double> bank_roll = bankRoll(path, heading, surface);
  auto interpolated = [&](const std::vector<double>& v, double s) {
    const auto it = std::upper_bound(cum.begin(), cum.end(), s);
    const std::size_t i = std::clamp<std::size_t>(it - cum.begin(), 1, cum.size() - 1);
    const double seg = cum[i] - cum[i - 1];
    const double a = seg > 0 ? std::clamp((s - cum[i - 1]) / seg, 0.0, 1.0) : 0.0;
    return v[i - 1] + a * (v[i] - v[i - 1]);
  };
  // Per-traversal truth and error draws.
  d.speed = U(P.speed_min, P.speed_max);
  const double lateral = P.lateral_offset_sigma * N01(rng);
  const double phase_p = U(0, 2 * kPi), phase_r = U(0, 2 * kPi);
  d.wheel_scale_error = P.wheel_scale_sigma * N01(rng) + P.wheel_scale_offset;
  d.gyro_bias = P.gyro_bias_sigma * drawVector3(N01, rng);
  const double bias_mag = U(P.gps_bias_min, P.gps_bias_max), bias_dir = U(0, 2 * kPi);
  d.gps_bias0 = bias_mag * Eigen::Vector2d(std::cos(bias_dir), std::sin(bias_dir));

  // True trajectory at the IMU rate.
  const double dt = 1.0 / P.imu_rate;
  const int n = static_cast<int>(std::floor(L / d.speed * P.imu_rate)) + 1;
  d.stamps.resize(n);
  d.truth.resize(n);
  d.distance.resize(n);
  for (int k = 0; k < n; ++k) {
    const double t = k * dt, s = std::min(L, d.speed * t);
    const double yaw = interpolated(heading, s);
    const Eigen::Vector3d p =
        pointAt(path, cum, s) + lateral * Eigen::Vector3d(-std::sin(yaw), std::cos(yaw), 0.0);
    const double pitch = interpolated(grade_pitch, s) +
                         P.pitch_amplitude * std::sin(2 * kPi * P.pitch_frequency * t + phase_p);
    const double roll = interpolated(bank_roll, s) +
                        P.roll_amplitude * std::sin(2 * kPi * P.roll_frequency * t + phase_r);
    d.stamps[k] = t;
    d.truth[k] = poseFromXyzRpy(p.x(), p.y(), p.z(), roll, pitch, yaw);
    d.distance[k] = k == 0 ? 0.0
                           : d.distance[k - 1] +
                                 (d.truth[k].translation() - d.truth[k - 1].translation()).norm();
  }
  synthesizeImu(d, P, N01, rng);
  mountImu(d.imu, P.imu_pitch_mount);  // an injected mount error (trust tests)
  synthesizeWheel(d, P, N01, rng);
  // Dead reckoning: yaw from the gyro, levelled roll/pitch, position from the wheel speed.
  d.odom.resize(n);
  const Eigen::Vector3d rpy0 = rpyFromRotation(d.truth[0].linear());
  double yaw_o = 0.0;
  Eigen::Vector3d p_o = Eigen::Vector3d::Zero();
  std::size_t w = 0;
  for (int k = 0; k < n; ++k) {
    if (k > 0) {
      yaw_o += d.imu[k - 1].gyro.z() * dt;
      while (w + 1 < d.wheel.size() && d.wheel[w + 1].stamp <= d.stamps[k - 1] + 1e-9) ++w;
      p_o += d.odom[k - 1].linear() * Eigen::Vector3d(d.wheel[w].speed * dt, 0, 0);
    }
    const Eigen::Vector3d rpy = rpyFromRotation(d.truth[k].linear());
    (void)rpy0;
    const double pitch_noise = N01(rng), roll_noise = N01(rng);  // in this order: draw_order.hpp
    d.odom[k] = poseFromXyzRpy(p_o.x(), p_o.y(), p_o.z(), rpy.x() + P.attitude_noise * roll_noise,
                               rpy.y() + P.attitude_noise * pitch_noise, yaw_o);
  }
  // GPS at the GPS rate: bias random walk + white noise + multipath outliers.
  Eigen::Vector2d bias = d.gps_bias0;
  const double gps_dt = 1.0 / P.gps_rate;
  for (double t = 0.0; t <= d.stamps.back() + 1e-9; t += gps_dt) {
    const int k = std::min(n - 1, static_cast<int>(std::lround(t * P.imu_rate)));
    if (t > 0.0) bias += P.gps_bias_walk * std::sqrt(gps_dt) * drawVector2(N01, rng);
    GpsRecord g;
    const Eigen::Vector3d white = drawVector3(N01, rng);
    g.error_enu =
        Eigen::Vector3d(bias.x() + P.gps_white_sigma * white.x(),
                        bias.y() + P.gps_white_sigma * white.y(), P.gps_vertical_sigma * white.z());
    if (U(0, 1) < P.gps_outlier_probability) {
      const double m = U(P.gps_outlier_min, P.gps_outlier_max), a = U(0, 2 * kPi);
      g.error_enu += Eigen::Vector3d(m * std::cos(a), m * std::sin(a), 0.0);
      g.outlier = true;
    }
    g.fix.stamp = d.stamps[k];
    g.fix.position = enu.toWgs84(d.truth[k].translation() + g.error_enu);
    g.fix.sigma_h = P.gps_reported_sigma_h;
    g.fix.sigma_v = P.gps_reported_sigma_v;
    d.gps.push_back(g);
  }
  return d;
}

std::size_t cameraStride(const DriveParams& DP) {
  return std::max<std::size_t>(1, std::lround(DP.imu_rate / DP.camera_rate));
}

}  // namespace mapfuse::sim
