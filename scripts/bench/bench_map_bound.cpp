// Where a crowdsourced map's absolute error comes from (issue 22, docs/localize.md "Where the
// error comes from"): the map's lane lines against the true ones, beside what the GPS of the
// traversals that built it allows. The simulator is run again in-process from its resolved
// configuration (simulate.config.json: same seed, same draws), so every GPS fix's true error and
// multipath flag are known exactly.
//
// Per lane-line sample point p of the map (every `step` m), n the unit normal of the nearest
// true lane line (across the road):
//   map      n . (p - true line)                        the map's lateral offset at p
//   bound    n . mean(e_f) over the inlier GPS fixes f of the map's traversals that drove past p
//            (within `radius` m, heading within 30 deg of the line): what those traversals' GPS
//            says on average where p is; a map anchored on that GPS cannot do better there
//            without other absolute information
//   global   n . mean(e_f) over all inlier fixes of all the map's traversals: the error of a map
//            whose shape is exact and whose placement is the least-squares fit to all the GPS
//   <stage>  n . mean(T_kf - T_true) over the keyframes of the stage's LSMs (georef, align
//            output) that drove past p: where that stage put the vehicles
//   <stage>_lines  n . the mean error of the stage's lane-line points near p (each against the
//            true line it observed, truth_id): where that stage put the lane lines
// RMS and mean absolute value over the points, the RMS of the differences to the bound and to
// the map, and what the GPS model predicts for the mean of the drives' errors, as one JSON line;
// with --csv, one row per 100 m cell. --debias-in/-out writes the oracle: a stage's LSMs with
// each drive's own mean GPS error (less the mean over all drives) taken off its keyframes.
//
//   bench_map_bound --sim out/sim --map work/aggregate/map.cbor \
//       --stage georef=work/georef --stage align=work/align [--csv cells.csv] MAP_LSM...
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <unordered_map>

#include "mapfuse/cli/app.hpp"
#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/eval/map_metrics.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/vector_map_io.hpp"
#include "mapfuse/localize/map_index.hpp"
#include "mapfuse/sim/crowd.hpp"
#include "mapfuse/stages/simulate.hpp"

using namespace mapfuse;
namespace fs = std::filesystem;

namespace {

constexpr double kParallelCos = 0.866;  // heading within 30 deg of the line: drove past it
constexpr double kCell = 100.0;         // m, the stretches of the per-cell table
// keyframe separations (about 8.5 m each) of the drives\' relative error
const std::vector<std::size_t> kRelativeSeparations = {1, 12, 24};

/// A sample of where something was placed and its error (2D, sim ENU).
struct Sample {
  Eigen::Vector2d p;    ///< true position, m
  Eigen::Vector2d dir;  ///< unit heading
  Eigen::Vector2d e;    ///< error (placed - true), m
};

/// Samples in a uniform grid for radius queries.
class SampleGrid {
 public:
  SampleGrid(std::vector<Sample> s, double cell) : s_(std::move(s)), cell_(cell) {
    for (std::size_t i = 0; i < s_.size(); ++i) cells_[key(s_[i].p)].push_back(i);
  }
  /// Mean error of the samples within `r` of p whose heading is parallel to `dir`; count in n.
  Eigen::Vector2d meanNear(const Eigen::Vector2d& p, const Eigen::Vector2d& dir, double r,
                           int* n) const {
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    *n = 0;
    const int64_t cx = std::floor(p.x() / cell_), cy = std::floor(p.y() / cell_);
    const int reach = static_cast<int>(std::ceil(r / cell_));
    for (int64_t ix = cx - reach; ix <= cx + reach; ++ix)
      for (int64_t iy = cy - reach; iy <= cy + reach; ++iy) {
        const auto it = cells_.find(pack(ix, iy));
        if (it == cells_.end()) continue;
        for (std::size_t i : it->second) {
          const Sample& s = s_[i];
          if ((s.p - p).norm() > r || std::abs(s.dir.dot(dir)) < kParallelCos) continue;
          sum += s.e;
          ++*n;
        }
      }
    return *n ? Eigen::Vector2d(sum / *n) : sum;
  }
  Eigen::Vector2d mean() const {
    Eigen::Vector2d m = Eigen::Vector2d::Zero();
    for (const auto& s : s_) m += s.e;
    return s_.empty() ? m : Eigen::Vector2d(m / double(s_.size()));
  }
  std::size_t size() const { return s_.size(); }

 private:
  static int64_t pack(int64_t ix, int64_t iy) { return (ix << 32) ^ (iy & 0xffffffff); }
  int64_t key(const Eigen::Vector2d& p) const {
    return pack(std::floor(p.x() / cell_), std::floor(p.y() / cell_));
  }
  std::vector<Sample> s_;
  double cell_;
  std::unordered_map<int64_t, std::vector<std::size_t>> cells_;
};

struct Segment {
  Eigen::Vector2d a, dir;  ///< start, unit direction
};

/// The segment of `line` nearest to q (horizontal).
Segment nearestSegment(const std::vector<Eigen::Vector3d>& line, const Eigen::Vector2d& q) {
  Segment best{line[0].head<2>(), Eigen::Vector2d::UnitX()};
  double best_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < line.size(); ++i) {
    const Eigen::Vector2d a = line[i - 1].head<2>(), ab = line[i].head<2>() - a;
    const double len2 = ab.squaredNorm();
    if (len2 <= 0) continue;
    const double t = std::clamp((q - a).dot(ab) / len2, 0.0, 1.0);
    const double d2 = (a + t * ab - q).squaredNorm();
    if (d2 < best_d2) best_d2 = d2, best = {a, ab / std::sqrt(len2)};
  }
  return best;
}

int traversalIndex(const std::string& drive_id) {
  const auto at = drive_id.rfind("_trav");
  if (at == std::string::npos)
    throw InputError("bench_map_bound: drive id '" + drive_id + "' is not simulate's");
  return std::stoi(drive_id.substr(at + 5));
}

Eigen::Vector2d headingOf(const Pose3& T) {
  return T.linear().col(0).head<2>().normalized();
}

struct Rms {
  double sq = 0, abs = 0;
  int n = 0;
  void add(double v) { sq += v * v, abs += std::abs(v), ++n; }
  double value() const { return n ? std::sqrt(sq / n) : 0.0; }
  double meanAbs() const { return n ? abs / n : 0.0; }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"the map's lateral error against what its traversals' GPS allows"};
  std::string sim_dir, map_file, csv;
  std::vector<std::string> stage_args, inputs;
  double step = 1.0, radius = 50.0, match_radius = 1.5;
  app.add_option("--sim", sim_dir, "simulate output folder (simulate.config.json, truth/)")
      ->required();
  app.add_option("--map", map_file, "the map (aggregate's map.cbor / map.json)")->required();
  app.add_option("--stage", stage_args, "NAME=DIR: a stage's LSMs in enu (georef, align)")
      ->allow_extra_args(false);
  app.add_option("--csv", csv, "per 100 m cell table (CSV)");
  app.add_option("--step", step, "m, lane-line sample spacing")->check(CLI::Range(0.1, 100.0));
  app.add_option("--radius", radius, "m, 'drove past p' radius")->check(CLI::Range(1.0, 1000.0));
  app.add_option("--match-radius", match_radius, "m, map point to true line")
      ->check(CLI::Range(0.1, 10.0));
  std::string debias_in, debias_out;
  app.add_option("--debias-in", debias_in,
                 "oracle: a stage's LSMs (georef output) to write with each drive's mean GPS "
                 "error (less the mean over all drives) taken off its keyframes");
  app.add_option("--debias-out", debias_out, "oracle: folder for them")->needs("--debias-in");
  app.add_option("lsms", inputs, "the map's input LSMs (their drive ids)")->required();
  return cli::run(app, argc, argv, [&] {
    stages::SimulateParams P;
    paramsFromFile(P, (fs::path(sim_dir) / "simulate.config.json").string());
    if (!P.map.empty()) throw ConfigError("bench_map_bound: procedural worlds only");
    const geo::GeoOrigin origin{P.origin_lat, P.origin_lon, P.origin_alt};
    const sim::World world = sim::proceduralWorld(P.crowd, origin);
    const sim::Crowd crowd(world, origin, P.crowd);
    const geo::EnuConverter enu(origin);

    // GPS inlier errors of the map's traversals, and their truth for the stages' keyframes
    std::vector<Sample> gps;
    std::map<std::string, sim::Drive> drives;
    std::map<std::string, Eigen::Vector2d> drive_mean;  // mean inlier GPS error per drive
    int outliers = 0;
    for (const auto& in : cli::expandInputList(inputs)) {
      const Lsm lsm = io::readLsm(in);
      sim::Drive d = crowd.traversal(traversalIndex(lsm.drive_id)).drive;
      if (d.drive_id != lsm.drive_id)
        throw InputError(in + ": drive " + lsm.drive_id + " is not traversal " + d.drive_id);
      Eigen::Vector2d sum = Eigen::Vector2d::Zero();
      int inliers = 0;
      for (const auto& g : d.gps) {
        if (g.outlier) {
          ++outliers;
          continue;
        }
        sum += g.error_enu.head<2>();
        ++inliers;
        const auto k = static_cast<std::size_t>(std::lround(g.fix.stamp * P.crowd.drive.imu_rate));
        const Pose3& T = d.truth[std::min(k, d.truth.size() - 1)];
        gps.push_back({T.translation().head<2>(), headingOf(T), g.error_enu.head<2>()});
      }
      drive_mean[lsm.drive_id] = inliers ? Eigen::Vector2d(sum / inliers) : sum;
      drives.emplace(lsm.drive_id, std::move(d));
    }
    const SampleGrid gps_grid(gps, radius);
    if (!debias_in.empty()) {  // the oracle: every drive's constant GPS error gone but the mean
      fs::create_directories(debias_out);
      const Eigen::Vector2d all = gps_grid.mean();
      for (const auto& f : fs::recursive_directory_iterator(debias_in)) {
        const std::string name = f.path().filename().string();
        if (!f.is_regular_file() || name.find(".lsm.") == std::string::npos) continue;
        Lsm lsm = io::readLsm(f.path());
        const auto it = drive_mean.find(lsm.drive_id);
        if (it == drive_mean.end()) continue;
        for (auto& kf : lsm.keyframes) kf.T_frame_body.translation().head<2>() -= it->second - all;
        io::writeLsm(fs::path(debias_out) / name, lsm);
      }
    }
    // What the GPS model predicts for the mean of the drives' errors, per axis: a drive's bias
    // (magnitude uniform in [a, b], direction uniform: E|b|^2 = (a^2 + ab + b^2) / 3, half per
    // axis) plus its random walk averaged over a drive of T s (variance walk^2 T / 3), over N
    // independent drives.
    const sim::DriveParams& DP = P.crowd.drive;
    double seconds = 0;
    for (const auto& [id, d] : drives) seconds += d.stamps.back();
    const double T = drives.empty() ? 0.0 : seconds / double(drives.size());
    const double a = DP.gps_bias_min, b = DP.gps_bias_max;
    const double per_drive_axis =
        std::sqrt((a * a + a * b + b * b) / 6.0 + DP.gps_bias_walk * DP.gps_bias_walk * T / 3.0);
    const double expected_axis =
        per_drive_axis / std::sqrt(std::max<std::size_t>(1, drives.size()));

    const VectorMap truth = io::readVectorMap(fs::path(sim_dir) / "truth" / "vector_map.json");
    const localize::MapIndex index(truth, /*use_attributes=*/false);
    const int key = localize::matchKey(CrowdClass::kLaneLine, {}, false);
    std::unordered_map<int64_t, const std::vector<Eigen::Vector3d>*> true_lines;
    for (const auto& inst : truth.instances)
      if (inst.cls == CrowdClass::kLaneLine && inst.points.size() >= 2)
        true_lines[inst.id] = &inst.points;

    // each stage's keyframe errors and lane-line point errors (across the true line), its LSMs
    // re-expressed in the simulator's ENU
    std::vector<std::pair<std::string, SampleGrid>> stages_grid;
    nlohmann::json relative_json = nlohmann::json::object();
    for (const auto& arg : stage_args) {
      const auto eq = arg.find('=');
      if (eq == std::string::npos) throw ConfigError("--stage wants NAME=DIR, got " + arg);
      std::vector<Sample> kfs, points;
      std::vector<Rms> relative(kRelativeSeparations.size());
      for (const auto& f : fs::recursive_directory_iterator(arg.substr(eq + 1))) {
        const std::string name = f.path().filename().string();
        if (!f.is_regular_file() || name.find(".lsm.") == std::string::npos) continue;
        const Lsm lsm = io::readLsm(f.path());
        const auto it = drives.find(lsm.drive_id);
        if (it == drives.end() || !lsm.origin) continue;
        const geo::EnuConverter from(*lsm.origin);
        const std::size_t first = kfs.size();
        for (const auto& kf : lsm.keyframes) {
          const auto k = static_cast<std::size_t>(std::lround(kf.stamp * P.crowd.drive.imu_rate));
          const Pose3& T = it->second.truth[std::min(k, it->second.truth.size() - 1)];
          const Eigen::Vector3d q = enu.toEnu(from.toWgs84(kf.T_frame_body.translation()));
          kfs.push_back(
              {T.translation().head<2>(), headingOf(T), q.head<2>() - T.translation().head<2>()});
        }
        // the drive's shape: error of the displacement between keyframes `sep` apart, across
        // the true heading
        for (std::size_t i = 0; i < kRelativeSeparations.size(); ++i)
          for (std::size_t a = first; a + kRelativeSeparations[i] < kfs.size(); ++a) {
            const Sample &s0 = kfs[a], &s1 = kfs[a + kRelativeSeparations[i]];
            relative[i].add(Eigen::Vector2d(-s0.dir.y(), s0.dir.x()).dot(s1.e - s0.e));
          }
        // compared with the true line they observe (truth_id), not the nearest one: a stage's
        // points may be metres off before align, and only those near a line would count
        for (const auto& el : lsm.elements) {
          const auto line = true_lines.find(el.truth_id);
          if (el.cls != CrowdClass::kLaneLine || line == true_lines.end()) continue;
          for (const auto& x : lsm.pointsInFrame(el)) {
            const Eigen::Vector2d q = enu.toEnu(from.toWgs84(x)).head<2>();
            const auto seg = nearestSegment(*line->second, q);
            const Eigen::Vector2d n(-seg.dir.y(), seg.dir.x());
            points.push_back({q, seg.dir, n * n.dot(q - seg.a)});
          }
        }
      }
      if (kfs.empty()) throw InputError(arg + ": no LSM of the map's drives");
      for (std::size_t i = 0; i < relative.size(); ++i)
        relative_json[arg.substr(0, eq)][std::to_string(kRelativeSeparations[i])] =
            relative[i].value();
      stages_grid.emplace_back(arg.substr(0, eq), SampleGrid(std::move(kfs), radius));
      stages_grid.emplace_back(arg.substr(0, eq) + "_lines", SampleGrid(std::move(points), radius));
    }

    // the map's lane-line samples against the true lane lines
    const VectorMap map = eval::inOrigin(io::readVectorMap(map_file), origin);
    const Eigen::Vector2d global = gps_grid.mean();
    const std::size_t columns = 3 + stages_grid.size();  // map, bound, global, stages...
    std::vector<Rms> rms(columns), diff_bound(columns), diff_map(columns);
    struct Cell {
      std::vector<Rms> rms;
      Rms diff;
      int traversal_fixes = 0;
    };
    std::map<std::pair<int64_t, int64_t>, Cell> cells;
    int samples = 0, matched = 0, no_gps = 0;
    Rms map_all;  // the map over every matched sample, GPS nearby or not
    for (const auto& inst : map.instances) {
      if (inst.cls != CrowdClass::kLaneLine) continue;
      for (std::size_t i = 1; i < inst.points.size(); ++i) {
        const Eigen::Vector2d a = inst.points[i - 1].head<2>(), b = inst.points[i].head<2>();
        const int pieces = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
        for (int j = 0; j < pieces; ++j) {
          const Eigen::Vector2d p = a + (b - a) * (double(j) / pieces);
          ++samples;
          const auto m = index.nearest(key, p, match_radius);
          if (!m.target || !m.target->is_line) continue;
          const Eigen::Vector2d dir = (m.target->b - m.target->a).normalized();
          const Eigen::Vector2d n(-dir.y(), dir.x());
          ++matched;
          map_all.add(n.dot(p - m.target->a));
          int fixes = 0;
          const Eigen::Vector2d bound = gps_grid.meanNear(p, dir, radius, &fixes);
          if (fixes == 0) {
            ++no_gps;
            continue;
          }
          std::vector<double> v{n.dot(p - m.target->a), n.dot(bound), n.dot(global)};
          for (const auto& [name, grid] : stages_grid) {
            int kfs = 0;
            v.push_back(n.dot(grid.meanNear(p, dir, radius, &kfs)));
          }
          auto& c = cells[{static_cast<int64_t>(std::floor(p.x() / kCell)),
                           static_cast<int64_t>(std::floor(p.y() / kCell))}];
          if (c.rms.empty()) c.rms.resize(columns);
          c.traversal_fixes += fixes;
          c.diff.add(v[0] - v[1]);
          for (std::size_t k = 0; k < columns; ++k) {
            rms[k].add(v[k]);
            c.rms[k].add(v[k]);
            diff_bound[k].add(v[k] - v[1]);
            diff_map[k].add(v[k] - v[0]);
          }
        }
      }
    }
    std::vector<std::string> names{"map", "bound", "global"};
    for (const auto& s : stages_grid) names.push_back(s.first);
    nlohmann::json j{
        {"lane_line_samples", samples},
        {"matched", matched},
        {"relative_lateral_rms_m_by_keyframe_separation", relative_json},
        {"without_gps_nearby", no_gps},
        {"map_all_matched", {{"rms_m", map_all.value()}, {"mean_abs_m", map_all.meanAbs()}}},
        {"gps_inlier_fixes", gps.size()},
        {"gps_outliers", outliers},
        {"drives", drives.size()},
        {"radius_m", radius},
        {"global_mean_gps_error_enu_m", {global.x(), global.y()}},
        {"drive_seconds_mean", T},
        {"expected_drive_gps_error_per_axis_m", per_drive_axis},
        {"expected_global_mean_per_axis_m", expected_axis},
        {"expected_global_mean_abs_lateral_m", expected_axis * std::sqrt(2.0 / M_PI)}};
    for (std::size_t k = 0; k < columns; ++k)
      j["lateral"][names[k]] = {{"rms_m", rms[k].value()},
                                {"mean_abs_m", rms[k].meanAbs()},
                                {"rms_minus_bound_m", diff_bound[k].value()},
                                {"rms_minus_map_m", diff_map[k].value()}};
    std::cout << j.dump() << "\n";
    if (!csv.empty()) {
      std::ofstream out(csv);
      out << "cell_x_m,cell_y_m,samples,fixes_per_sample";
      for (const auto& n : names) out << "," << n << "_rms_m";
      out << ",map_minus_bound_rms_m\n";
      for (const auto& [xy, c] : cells) {
        out << xy.first * kCell << "," << xy.second * kCell << "," << c.diff.n << ","
            << c.traversal_fixes / std::max(1, c.diff.n);
        for (const auto& r : c.rms) out << "," << r.value();
        out << "," << c.diff.value() << "\n";
      }
      if (!out) throw IoError(csv, "cannot write");
    }
  });
}
