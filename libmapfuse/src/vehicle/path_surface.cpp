#include "path_surface.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace mapfuse::vehicle {
namespace {
/// Path searched ahead for the frame abreast, beyond the farthest ranged point: the path bends,
/// and a point at max_range is passed after more than max_range of path.
constexpr double kReachMargin = 1.5;
/// m, how far the road abreast may be from the path's heights (their noise, 1-2 cm, and the
/// tangent's pitch error, ~2e-3 rad over 20 m) when a ray's ranging is checked for conditioning.
constexpr double kSurfaceTol = 0.05;
/// Share of its range a point may move when the road is kSurfaceTol lower: a flat road moves a
/// point at the band's 30 m edge by 3.6 %; a ray skimming a crest by tens of metres.
constexpr double kMaxRangeShift = 0.1;
/// rad: the path from frame i to the frame abreast turned by more than this, and a point farther
/// aside than path_max_offset is not ranged on the road there. Where the drive turns off, a
/// point on the road straight on is "abreast" of a frame far along the new road, whose plane
/// says nothing of it: unbounded, lane points 10-15 m aside 0.17 -> 1.5 m RMS (flat world) and
/// 15-30 m ahead 0.10 -> 0.23 m (8 % world); gated at 0.3 rad, 0.10 m, while a crossing road's
/// stop lines 15-25 m aside of a straight path keep the road's own cross-slope.
constexpr double kStraightTurn = 0.3;
/// Share of the reach the parabola also spans behind the frame (its d ∈ [-share reach, reach]):
/// measured on the 8 % and the flat world (tests/vehicle/test_path_surface.cpp), 0.5 left the
/// flat world's far lane points 16 % worse than the plane under the camera, 1.0 8 %, 2.0 smooths
/// the hills' bends away (0.18 m against 0.13 m on the 8 % world).
constexpr double kFitBehindShare = 1.0;
/// Frames the parabola needs (fewer, e.g. at a standstill or the drive's ends: no bend).
constexpr int kFitMinFrames = 10;

/// m RMS: heights that a parabola fits this well are the road's profile plus the dead reckoning's
/// own height noise (measured over ±45 m on the flat and the 8 % world: median 1.8-2.0 cm, at most
/// 3.5 cm at the drive's start); a worse fit means the road bends more than one parabola can
/// follow (esmini crest-curve: 0.1-0.45 m) and the profile itself is taken.
constexpr double kBendFitNoise = 0.05;
/// How much the body's left axes decide the up axis against their mean up (heightProfile): the
/// left axes' spread where the drive turns 30° is ~0.02, their roll noise ~3e-5.
constexpr double kLevelWeight = 1e-3;
/// Share of the reach over which the road's slope is fitted where no parabola follows the road.
constexpr double kTangentWindow = 0.25;
/// m, half-width of the moving average of the heights used as the profile there.
constexpr double kProfileSmooth = 2.0;

/// Moving average of z over the frames within ±half of each frame's path distance.
std::vector<double> smoothAlongPath(const std::vector<double>& d, const std::vector<double>& z,
                                    double half) {
  const std::size_t n = d.size();
  std::vector<double> out(n, 0.0);
  std::size_t lo = 0, hi = 0;
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    while (hi < n && d[hi] <= d[i] + half) sum += z[hi++];
    while (d[lo] < d[i] - half) sum -= z[lo++];
    out[i] = sum / double(hi - lo);
  }
  return out;
}

struct BendFit {
  double b = 0.0;    ///< road slope at the frame, z ≈ a + b d + c d²
  double c = 0.0;    ///< 1/m
  double rms = 0.0;  ///< m, residual of the fit
};

/// Least-squares parabola of z against d over frames [lo, hi) (d relative to frame i); c = 0 when
/// the frames do not span enough path for a parabola.
BendFit fitBend(const std::vector<double>& d, const std::vector<double>& z, std::size_t i,
                std::size_t lo, std::size_t hi, double span_min) {
  if (int(hi - lo) < kFitMinFrames || d[hi - 1] - d[lo] < span_min) return {};
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (std::size_t k = lo; k < hi; ++k) {
    const double x = d[k] - d[i];
    const Eigen::Vector3d row(1.0, x, x * x);
    A += row * row.transpose();
    b += row * (z[k] - z[i]);
  }
  const Eigen::Vector3d coef = A.ldlt().solve(b);
  if (!coef.allFinite()) return {};
  double ss = 0.0;
  for (std::size_t k = lo; k < hi; ++k) {
    const double x = d[k] - d[i];
    const double r = z[k] - z[i] - coef.dot(Eigen::Vector3d(1.0, x, x * x));
    ss += r * r;
  }
  return {coef.y(), coef.z(), std::sqrt(ss / double(hi - lo))};
}
}  // namespace

namespace {
/// The drive's height profile: path distance and height (along the drive's mean up axis) per frame.
struct Profile {
  std::vector<double> distance, z;
};

Profile heightProfile(const std::vector<Pose3>& T_odom_body) {
  const std::size_t n = T_odom_body.size();
  Profile p{std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)};
  // The up axis, in any odom frame. The body's up axes lean back by the grade: their mean is
  // tilted by the drive's mean grade, and along a tilted axis a horizontal curve reads as a bend
  // (esmini curves_elevation: 6 cm 15 m ahead). Their left axes are level whatever the grade
  // (roads are level across, up to crossfall): where the drive turns they span the horizontal
  // and fix the up; where it runs straight the mean up stands (and a straight path shows no
  // bend along it). up = (I + L / kLevelWeight)⁻¹ z̄, L the left axes' mean outer product.
  Eigen::Vector3d mean_up = Eigen::Vector3d::Zero();
  Eigen::Matrix3d L = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0)
      p.distance[k] = p.distance[k - 1] +
                      (T_odom_body[k].translation() - T_odom_body[k - 1].translation()).norm();
    mean_up += T_odom_body[k].linear().col(2);
    const Eigen::Vector3d left = T_odom_body[k].linear().col(1);
    L += left * left.transpose();
  }
  if (n == 0 || !(mean_up.norm() > 0)) return p;
  mean_up /= double(n);
  L /= double(n);
  Eigen::Vector3d up =
      (Eigen::Matrix3d::Identity() + L / kLevelWeight).ldlt().solve(mean_up).normalized();
  if (!up.allFinite()) up = mean_up.normalized();
  for (std::size_t k = 0; k < n; ++k) p.z[k] = up.dot(T_odom_body[k].translation());
  return p;
}

/// Per frame the parabola over [-behind reach, reach] of path (fitBend).
std::vector<BendFit> fitBends(const Profile& p, double reach) {
  const std::size_t n = p.distance.size();
  std::vector<BendFit> out(n);
  std::size_t lo = 0, hi = 0;  // frames [lo, hi) with d in [-behind reach, reach] around frame i
  for (std::size_t i = 0; i < n; ++i) {
    while (p.distance[lo] < p.distance[i] - kFitBehindShare * reach) ++lo;
    while (hi < n && p.distance[hi] <= p.distance[i] + reach) ++hi;
    out[i] = fitBend(p.distance, p.z, i, lo, hi, 0.5 * reach);
  }
  return out;
}
}  // namespace

std::vector<bool> sharpVerticalCurves(const std::vector<Pose3>& T_odom_body,
                                      const RangingSettings& settings) {
  const auto fits = fitBends(heightProfile(T_odom_body), kReachMargin * settings.max_range);
  std::vector<bool> out(fits.size());
  for (std::size_t i = 0; i < fits.size(); ++i) out[i] = fits[i].rms > kBendFitNoise;
  return out;
}

PathSurface::PathSurface(const std::vector<Pose3>& T_odom_body, const Pose3& T_body_cam,
                         const std::vector<GroundPlane>& planes, const RangingSettings& settings)
    : T_odom_body_(T_odom_body),
      planes_(planes),
      max_offset_(settings.path_max_offset),
      reach_(kReachMargin * settings.max_range) {
  const std::size_t n = T_odom_body.size();
  T_body_odom_.reserve(n);
  T_odom_cam_.reserve(n);
  for (const Pose3& T : T_odom_body) {
    T_body_odom_.push_back(T.inverse());
    T_odom_cam_.push_back(T * T_body_cam);
  }
  const Profile p = heightProfile(T_odom_body);
  distance_ = p.distance;
  // Per frame: its ground plane's normal (up) and the road's direction across (left), in odom.
  up_.resize(n);
  across_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    up_[k] = (T_odom_body[k].linear() * T_body_cam.linear() * planes[k].normal_cam).normalized();
    across_[k] = up_[k].cross(T_odom_body[k].linear().col(0)).normalized();
  }
  const std::vector<double>& z = p.z;
  height_ = smoothAlongPath(distance_, z, kProfileSmooth);
  // Per frame: the parabola over the whole window where it follows the heights within
  // kBendFitNoise; else the profile itself, against the tangent of a short parabola.
  const auto wide = fitBends(p, reach_), narrow = fitBends(p, kTangentWindow * reach_);
  bend_.resize(n);
  slope_.resize(n);
  profile_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    bend_[i] = wide[i].c;
    profile_[i] = wide[i].rms > kBendFitNoise;
    slope_[i] = narrow[i].b;
  }
}

namespace {
/// The camera's view direction (z) within the plane of normal n: "ahead" for a road's slope.
Eigen::Vector3d viewAhead(const Eigen::Vector3d& n) {
  return (Eigen::Vector3d::UnitZ() - n.z() * n).normalized();
}
}  // namespace

bool PathSurface::turned(std::size_t i, std::size_t j) const {
  const Eigen::Vector2d a = T_odom_body_[i].linear().col(0).head<2>(),
                        b = T_odom_body_[j].linear().col(0).head<2>();
  return a.normalized().dot(b.normalized()) < std::cos(kStraightTurn);
}

double PathSurface::slopeAhead(std::size_t i, std::size_t j) const {
  if (profile_[i]) return slope_[j] - slope_[i];
  return 2.0 * bend_[i] * (distance_[j] - distance_[i]);
}

double PathSurface::riseAhead(std::size_t i, std::size_t j) const {
  const double d = distance_[j] - distance_[i];
  if (profile_[i]) return height_[j] - height_[i] - slope_[i] * d;
  return bend_[i] * d * d;
}

std::optional<PathSurface::Meeting> PathSurface::meet(std::size_t i, std::size_t j,
                                                      const Eigen::Vector2d& pixel,
                                                      const Eigen::Matrix3d& K_inv,
                                                      double rise) const {
  GroundPlane ahead = planes_[i];
  ahead.height -= rise;
  if (!(ahead.height > 0.0)) return std::nullopt;     // the road there rises above the camera
  auto X = backProjectToGround(pixel, K_inv, ahead);  // eq. (1) on the road there
  if (!X) return std::nullopt;
  // Twist. The rise is the path's own height abreast of j. The road there is flat along frame
  // j's ground plane across the path, not along frame i's: a point `aside` of the path abreast of
  // j lies n_i · across_j · aside higher (n_i frame i's plane normal). On a curve up a grade b
  // this is b sin(ψ_j − ψ_i) aside (esmini curves_elevation, 8 % on R ≈ 100 m: 6 cm 15 m ahead
  // and 5 m aside; lane points 0.15-0.18 m off across the road without it); where the
  // cross-slope changes ahead (superelevation runs) it is that change.
  const Pose3& T_odom_cam_i = T_odom_cam_[i];
  const double aside = (T_body_odom_[j] * (T_odom_cam_i * *X)).y();  // stable before the
  const double twist = aside * up_[i].dot(across_[j]);                // crossing too
  ahead.height -= twist;
  X = ahead.height > 0.0 ? backProjectToGround(pixel, K_inv, ahead) : std::nullopt;
  if (!X) return std::nullopt;
  return Meeting{T_body_odom_[j] * (T_odom_cam_i * *X), rise + twist};
}

std::optional<PathSurface::Crossing> PathSurface::beyondEnd(std::size_t i,
                                                           const Eigen::Vector2d& pixel,
                                                           const Eigen::Matrix3d& K_inv,
                                                           double lowered) const {
  // The road beyond the drive's last frame L is L's own ground plane (the road it stood on, as
  // its camera saw it), carried into frame i's camera by the dead-reckoned poses: no fit of the
  // path's heights enters, whose slope at a drive's end is one-sided (measured: relative slopes
  // of 3.6 % where the drive turned into its last road).
  const std::size_t L = T_odom_body_.size() - 1;
  const Pose3 T_cami_camL = T_odom_cam_[i].inverse() * T_odom_cam_[L];
  const Eigen::Vector3d n = T_cami_camL.linear() * planes_[L].normal_cam;
  const Eigen::Vector3d on_road = T_cami_camL * (-planes_[L].height * planes_[L].normal_cam);
  const GroundPlane road{n, -n.dot(on_road) - lowered};
  if (!(road.height > 0.0)) return std::nullopt;
  const auto X = backProjectToGround(pixel, K_inv, road);
  if (!X) return std::nullopt;
  const Eigen::Vector3d q = T_body_odom_[L] * (T_odom_cam_[i] * *X);
  if (q.x() < 0.0 || (std::abs(q.y()) > max_offset_ && turned(i, L))) return std::nullopt;
  // As a rise of frame i's plane through the same point, and the road's slope against it along
  // the view (range() tilts the covariance's plane by it).
  const Eigen::Vector3d& n_i = planes_[i].normal_cam;
  const Eigen::Vector3d ahead_dir = viewAhead(n_i);
  const double rise = planes_[i].height + n_i.dot(*X);
  return Crossing{true, rise, -n.dot(ahead_dir) / n.dot(n_i)};
}

std::optional<PathSurface::Crossing> PathSurface::cross(std::size_t i, const Eigen::Vector2d& pixel,
                                                        const Eigen::Matrix3d& K_inv,
                                                        double lowered) const {
  // March along the path: the ray meets the road abreast of frame j where its intersection with
  // the tangent plane raised to frame j's road is no longer ahead of frame j. (Re-ranging on the
  // road abreast of the last estimate instead converges slowly or not at all on a crest, where a
  // rise error of δ moves the point ~δ d / h: 1.6 m at 20 m ranged 10-12 m.)
  double x_prev = 0.0, rise_prev = 0.0;  // frame j - 1's: ahead of it (x > 0), and its rise
  bool have_prev = false;
  for (std::size_t j = i + 1; j < T_odom_body_.size(); ++j) {
    if (distance_[j] - distance_[i] > reach_) return Crossing{false, 0.0, 0.0};  // missed it
    const double rise0 = riseAhead(i, j) - lowered;  // the road abreast of j above the tangent
    if (!(planes_[i].height - rise0 > 0.0)) return std::nullopt;  // above the camera
    const auto m = meet(i, j, pixel, K_inv, rise0);
    if (!m) {  // the road there is above the ray
      have_prev = false;
      continue;
    }
    if (m->q.x() > 0.0) {  // the ray meets that road beyond frame j
      x_prev = m->q.x(), rise_prev = m->rise, have_prev = true;
      continue;
    }
    if (std::abs(m->q.y()) > max_offset_ && turned(i, j)) return std::nullopt;
    // Crossed between frames j - 1 and j: the rise and slope interpolated where x passes 0.
    const double t = have_prev ? x_prev / (x_prev - m->q.x()) : 1.0;
    const double slope_prev = slopeAhead(i, have_prev ? j - 1 : j);
    return Crossing{true, (1.0 - t) * rise_prev + t * m->rise,
                    (1.0 - t) * slope_prev + t * slopeAhead(i, j)};
  }
  // The drive ends before the ray meets the road: still ahead of the last frame.
  if (have_prev) return beyondEnd(i, pixel, K_inv, lowered);
  return std::nullopt;
}

std::optional<GroundPoint> PathSurface::range(std::size_t i, const Eigen::Vector2d& pixel,
                                              const Eigen::Matrix3d& K,
                                              const RangingSettings& ranging, bool* on_path) const {
  if (on_path) *on_path = false;
  const Eigen::Matrix3d K_inv = K.inverse();
  GroundPlane plane = planes_[i];
  if (!backProjectToGround(pixel, K_inv, plane)) return std::nullopt;  // eq. (1) under the camera
  const auto c = cross(i, pixel, K_inv, 0.0);
  // The path runs on beyond the reach and the ray never meets the road along it: it passes over
  // a crest (or the point lies beyond the reach); the plane under the camera would range it
  // short. Not ranged.
  if (c && !c->met) return std::nullopt;
  GroundPlane raised = planes_[i];
  if (c) raised.height -= c->rise;
  const auto at = c ? backProjectToGround(pixel, K_inv, raised) : std::nullopt;
  if (at && raised.height > 0.0) {
    // Conditioning: the same ray with the road kSurfaceTol lower. A ray that runs close along
    // the road (over a crest) meets it somewhere else entirely: not ranged at all.
    const auto low = cross(i, pixel, K_inv, kSurfaceTol);
    GroundPlane lowered = planes_[i];
    if (low) lowered.height -= low->rise;
    const auto at_low = low ? backProjectToGround(pixel, K_inv, lowered) : std::nullopt;
    if (!at_low || !low->met || std::abs(at_low->norm() - at->norm()) > kMaxRangeShift * at->norm())
      return std::nullopt;
    // The covariance on the road's own plane there, through the same point: where the road
    // turns away from the ray the incidence is shallower than on the tangent plane.
    const Eigen::Vector3d n = raised.normal_cam;
    const Eigen::Vector3d ahead_dir = viewAhead(n);
    plane.normal_cam = (n - c->slope * ahead_dir).normalized();  // rising road: leans back
    plane.height = -plane.normal_cam.dot(*at);
  }
  // The band and the covariance on the plane finally used.
  auto g = rangeGroundPixel(pixel, K, plane, ranging);
  if (g && on_path) *on_path = at.has_value() && raised.height > 0.0;
  return g;
}

}  // namespace mapfuse::vehicle
