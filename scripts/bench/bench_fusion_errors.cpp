// Element spread / absolute error and keyframe ATE of georef or align output against the
// simulator's truth (eval::elementTruthErrors, docs/performance-fusion-accuracy.md).
//
//   bench_fusion_errors --sim out/sim LSM...      -> one JSON line on stdout
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "mapfuse/cli/app.hpp"
#include "mapfuse/eval/truth_errors.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/vector_map_io.hpp"

using namespace mapfuse;

int main(int argc, char** argv) {
  CLI::App app{"fusion errors vs simulate truth"};
  std::string sim;
  std::vector<std::string> inputs;
  app.add_option("--sim", sim, "simulate output folder (truth/ inside)")->required();
  app.add_option("lsms", inputs, "LSM files in enu")->required();
  return cli::run(app, argc, argv, [&] {
    const std::filesystem::path truth_dir = std::filesystem::path(sim) / "truth";
    std::vector<Lsm> lsms;
    std::map<std::string, eval::TrueTrajectory> traj;
    double gps_bias = 0;
    for (const auto& in : cli::expandInputList(inputs)) {
      lsms.push_back(io::readLsm(in));
      const auto p = truth_dir / (lsms.back().drive_id + ".trajectory.json");
      traj[lsms.back().drive_id] = eval::readTrueTrajectory(p);
      const auto doc = io::readDocument(p);
      const auto& b = doc.at("sensor_errors").at("gps_initial_bias_enu");
      gps_bias += std::hypot(b.at(0).get<double>(), b.at(1).get<double>());
    }
    const VectorMap truth = io::readVectorMap(truth_dir / "vector_map.json");
    const auto e = eval::elementTruthErrors(lsms, truth);
    const auto t = eval::trajectoryTruthErrors(lsms, traj);
    nlohmann::json j{{"drives", lsms.size()},
                     {"gps_bias_mean_m", gps_bias / double(lsms.size())},
                     {"observations", e.observations},
                     {"groups", e.groups},
                     {"element_abs_m", e.mean_abs},
                     {"element_spread_m", e.spread},
                     {"element_spread_median_m", e.spread_median},
                     {"element_common_offset_m", e.mean_offset},
                     {"ate_mean_m", t.ate_mean},
                     {"ate_max_m", t.ate_max},
                     {"drive_shift_mean_m", t.bias_mean}};
    std::cout << j.dump() << "\n";
  });
}
