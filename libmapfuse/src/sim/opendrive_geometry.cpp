#include "opendrive_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include "mapfuse/core/angles.hpp"

namespace mapfuse::sim {

namespace {

constexpr double kFresnelEps = 1e-16;
constexpr int kFresnelMaxIterations = 300;
constexpr double kFresnelSeriesLimit = 1.5;
constexpr double kTinyCurvatureRate = 1e-13;  // 1/m^2; below it a spiral is an arc
constexpr double kPoly3Step = 0.05;           // m of u between arc-length table samples

/// Index of the record with the largest start <= s + tolerance (0 when s precedes all), by
/// binary search on the records sorted by s (io/opendrive.cpp sorts them): O(log n) per lookup,
/// so a road of 100,000 records costs its length, not length x records.
template <class T>
std::size_t recordIndex(const std::vector<T>& records, double s, double tolerance = 0.0) {
  const auto it = std::upper_bound(records.begin(), records.end(), s + tolerance,
                                   [](double v, const T& r) { return v < r.s; });
  return it == records.begin() ? 0 : static_cast<std::size_t>(it - records.begin()) - 1;
}

/// The record with the largest start <= s (the first when s precedes all; none when empty).
template <class T>
const T* recordAt(const std::vector<T>& records, double s) {
  return records.empty() ? nullptr : &records[recordIndex(records, s)];
}

double poly(double a, double b, double c, double d, double x) {
  return a + x * (b + x * (c + x * d));
}

/// Arc length of u -> (u, v(u)) at uniform u samples (Simpson per step).
std::vector<double> poly3ArcTable(const io::OdrGeometry& g) {
  auto speed = [&](double u) {
    const double dv = g.b + u * (2 * g.c + u * 3 * g.d);
    return std::sqrt(1.0 + dv * dv);
  };
  std::vector<double> arc = {0.0};
  for (double u = 0.0; arc.back() < g.length + kPoly3Step; u += kPoly3Step)
    arc.push_back(arc.back() +
                  kPoly3Step / 6.0 *
                      (speed(u) + 4 * speed(u + 0.5 * kPoly3Step) + speed(u + kPoly3Step)));
  return arc;
}

/// u at arc length ds along a poly3, by the table and one Newton step.
double poly3U(const io::OdrGeometry& g, const std::vector<double>& arc, double ds) {
  const auto it = std::upper_bound(arc.begin(), arc.end(), ds);
  const std::size_t i = std::clamp<std::size_t>(it - arc.begin(), 1, arc.size() - 1);
  const double f = (ds - arc[i - 1]) / (arc[i] - arc[i - 1]);
  double u = (double(i - 1) + f) * kPoly3Step;
  // Newton on arc(u) - ds with arc(u) = table + Simpson on the remainder.
  const double u0 = double(i - 1) * kPoly3Step;
  auto speed = [&](double x) {
    const double dv = g.b + x * (2 * g.c + x * 3 * g.d);
    return std::sqrt(1.0 + dv * dv);
  };
  for (int k = 0; k < 3; ++k) {
    const double h = u - u0;
    const double a = arc[i - 1] + h / 6.0 * (speed(u0) + 4 * speed(u0 + 0.5 * h) + speed(u));
    u -= (a - ds) / speed(u);
  }
  return u;
}

RefPose evalPoly3(const io::OdrGeometry& g, const std::vector<double>& arc, double ds) {
  const double u = poly3U(g, arc, ds);
  const double v = poly(g.a, g.b, g.c, g.d, u);
  const double dv = g.b + u * (2 * g.c + u * 3 * g.d);
  const double c = std::cos(g.hdg), s = std::sin(g.hdg);
  return {g.x + c * u - s * v, g.y + s * u + c * v, g.hdg + std::atan2(dv, 1.0)};
}

}  // namespace

void fresnel(double x, double* C, double* S) {
  const double ax = std::abs(x);
  double c = 0.0, s = 0.0;
  if (ax < 1e-150) {
    c = ax;
  } else if (ax <= kFresnelSeriesLimit) {
    // C = sum_k even (-1)^(k/2) t_k / (2k + 1), S = sum_k odd (-1)^((k-1)/2) t_k / (2k + 1)
    // with t_k = x (pi x^2 / 2)^k / k!.
    const double fact = 0.5 * kPi * ax * ax;
    double term = ax, sum_c = ax, sum_s = 0.0;
    for (int k = 1; k < kFresnelMaxIterations; ++k) {
      term *= fact / k;
      const double sign = ((k / 2) % 2 == 0) ? 1.0 : -1.0;
      if (k % 2 == 1)
        sum_s += sign * term / (2 * k + 1);
      else
        sum_c += sign * term / (2 * k + 1);
      if (k > 2 && term < kFresnelEps * (std::abs(sum_c) + std::abs(sum_s))) break;
    }
    c = sum_c;
    s = sum_s;
  } else {
    // C + i S = (1 + i)/2 (1 - e^(i pi x^2 / 2) h), h from the continued fraction of
    // erfc((1 - i) sqrt(pi) x / 2) (modified Lentz; Numerical Recipes 6.9).
    const double pix2 = kPi * ax * ax;
    std::complex<double> b(1.0, -pix2), cc(1e300, 0.0), d = 1.0 / b, h = d;
    int n = -1;
    for (int k = 2; k <= kFresnelMaxIterations; ++k) {
      n += 2;
      const double a = -double(n) * (n + 1);
      b += 4.0;
      d = 1.0 / (a * d + b);
      cc = b + a / cc;
      const std::complex<double> del = cc * d;
      h *= del;
      if (std::abs(del.real() - 1.0) + std::abs(del.imag()) < kFresnelEps) break;
    }
    h *= std::complex<double>(ax, -ax);
    const std::complex<double> cs =
        std::complex<double>(0.5, 0.5) *
        (1.0 - std::complex<double>(std::cos(0.5 * pix2), std::sin(0.5 * pix2)) * h);
    c = cs.real();
    s = cs.imag();
  }
  *C = x < 0 ? -c : c;
  *S = x < 0 ? -s : s;
}

RefPose evalGeometry(const io::OdrGeometry& g, double ds) {
  const double c0 = std::cos(g.hdg), s0 = std::sin(g.hdg);
  switch (g.kind) {
    case io::OdrGeometry::Kind::kLine: return {g.x + c0 * ds, g.y + s0 * ds, g.hdg};
    case io::OdrGeometry::Kind::kArc: {
      const double k = g.curvature;
      if (std::abs(k) < 1e-15) return {g.x + c0 * ds, g.y + s0 * ds, g.hdg};
      const double h = g.hdg + k * ds;
      return {g.x + (std::sin(h) - s0) / k, g.y - (std::cos(h) - c0) / k, h};
    }
    case io::OdrGeometry::Kind::kSpiral: {
      const double k0 = g.curv_start;
      const double rate = g.length > 0 ? (g.curv_end - g.curv_start) / g.length : 0.0;
      const double h = g.hdg + k0 * ds + 0.5 * rate * ds * ds;
      if (std::abs(rate) < kTinyCurvatureRate) {  // an arc (or a line) for all practical purposes
        io::OdrGeometry arc = g;
        arc.kind = io::OdrGeometry::Kind::kArc;
        arc.curvature = k0 + 0.5 * rate * ds;
        RefPose p = evalGeometry(arc, ds);
        p.hdg = h;
        return p;
      }
      // theta(ds) = theta0 + (rate / 2) sigma^2 with sigma = ds + k0 / rate and
      // theta0 = hdg - k0^2 / (2 rate); sigma = tau sqrt(pi / |rate|) turns the position
      // integrals into Fresnel integrals of tau.
      const double sign = rate > 0 ? 1.0 : -1.0;
      const double scale = std::sqrt(kPi / std::abs(rate));
      const double theta0 = g.hdg - k0 * k0 / (2.0 * rate);
      const double tau0 = (k0 / rate) / scale, tau1 = (ds + k0 / rate) / scale;
      double C0, S0, C1, S1;
      fresnel(tau0, &C0, &S0);
      fresnel(tau1, &C1, &S1);
      const double dC = C1 - C0, dS = S1 - S0;
      const double ct = std::cos(theta0), st = std::sin(theta0);
      return {g.x + scale * (ct * dC - sign * st * dS), g.y + scale * (st * dC + sign * ct * dS),
              h};
    }
    case io::OdrGeometry::Kind::kPoly3: return evalPoly3(g, poly3ArcTable(g), ds);
    case io::OdrGeometry::Kind::kParamPoly3: {
      const double p = g.p_normalized ? (g.length > 0 ? ds / g.length : 0.0) : ds;
      const double u = poly(g.au, g.bu, g.cu, g.du, p);
      const double v = poly(g.av, g.bv, g.cv, g.dv, p);
      const double du = g.bu + p * (2 * g.cu + p * 3 * g.du);
      const double dv = g.bv + p * (2 * g.cv + p * 3 * g.dv);
      return {g.x + c0 * u - s0 * v, g.y + s0 * u + c0 * v, g.hdg + std::atan2(dv, du)};
    }
  }
  return {g.x, g.y, g.hdg};
}

RoadGeometry::RoadGeometry(const io::OdrRoad& road) : road_(road) {
  poly3_arc_.resize(road.plan_view.size());
  for (std::size_t i = 0; i < road.plan_view.size(); ++i)
    if (road.plan_view[i].kind == io::OdrGeometry::Kind::kPoly3)
      poly3_arc_[i] = poly3ArcTable(road.plan_view[i]);
}

RefPose RoadGeometry::reference(double s) const {
  s = std::clamp(s, 0.0, road_.length);
  const std::size_t i = recordIndex(road_.plan_view, s, 1e-9);
  const io::OdrGeometry& g = road_.plan_view[i];
  const double ds = std::clamp(s - g.s, 0.0, g.length);
  if (g.kind == io::OdrGeometry::Kind::kPoly3) return evalPoly3(g, poly3_arc_[i], ds);
  return evalGeometry(g, ds);
}

double RoadGeometry::laneOffset(double s) const {
  const io::OdrPoly3* o = recordAt(road_.lane_offset, s);
  return o ? o->at(s) : 0.0;
}

Eigen::Vector3d RoadGeometry::point(double s, double t) const {
  const RefPose r = reference(s);
  const io::OdrPoly3* e = recordAt(road_.elevation, s);
  const io::OdrPoly3* se = recordAt(road_.superelevation, s);
  const double roll = se ? se->at(s) : 0.0;
  const double lateral = t * std::cos(roll);
  return {r.x - lateral * std::sin(r.hdg), r.y + lateral * std::cos(r.hdg),
          (e ? e->at(s) : 0.0) + t * std::sin(roll)};
}

double RoadGeometry::laneWidth(std::size_t section, int id, double s) const {
  const io::OdrLaneSection& sec = road_.sections[section];
  const io::OdrLane* lane = sec.lane(id);
  if (!lane || id == 0 || lane->widths.empty()) return 0.0;
  const double ds = s - sec.s;
  // Negative widths (tapers overshooting zero) are 0; sim/opendrive_checks.cpp warns of them.
  return std::max(0.0, recordAt(lane->widths, ds)->at(ds));
}

double RoadGeometry::borderT(std::size_t section, int id, double s) const {
  double t = laneOffset(s);
  const int step = id > 0 ? 1 : -1;
  for (int k = step; id != 0 && k != id + step; k += step) t += step * laneWidth(section, k, s);
  return t;
}

double RoadGeometry::sectionStart(std::size_t section) const {
  return road_.sections[section].s;
}

double RoadGeometry::sectionEnd(std::size_t section) const {
  return section + 1 < road_.sections.size() ? road_.sections[section + 1].s : road_.length;
}

}  // namespace mapfuse::sim
