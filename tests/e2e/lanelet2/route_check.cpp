// route_check: does Lanelet2's routing graph (German rules, vehicle) connect the lanelets each
// drive passed, in the order it passed them? Compiled by tests/e2e/lanelet2_validate.sh against
// the real Lanelet2 library built from ../shared/tools/lanelet2 (never part of the library).
//   usage: route_check MAP.osm LSM...   (LSMs in ENU: georef or align outputs, one origin)
// Every keyframe position (ENU of the LSM's origin) goes to WGS84 (GeographicLib's local
// cartesian frame, as mapfuse's geo/), then into the map's frame by Lanelet2's UTM projector with
// the same origin. At each keyframe the drive is on the passable lanelet that contains it and
// runs its way (a two-way lanelet in either direction; the lanelet it was on before wins a tie);
// keyframes outside every lanelet (an unmarked stretch) are skipped. Consecutive distinct
// lanelets form the drive's pairs; a pair counts as connected when shortestPath finds a route.
// Prints one line per drive and a total line:
//   drive NAME: keyframes=K on_lanelets=L pairs=N routed=M share=S
//   total: pairs=N routed=M share=S
// followed by up to 5 unrouted pairs. Exit 0 (the caller judges the share), 2 on usage, 3 on a
// map with load errors or an LSM it cannot read.
#include <GeographicLib/LocalCartesian.hpp>
#include <lanelet2_core/LaneletMap.h>
#include <lanelet2_core/geometry/Lanelet.h>
#include <lanelet2_core/geometry/LaneletMap.h>
#include <lanelet2_io/Io.h>
#include <lanelet2_projection/UTM.h>
#include <lanelet2_routing/RoutingGraph.h>
#include <lanelet2_traffic_rules/TrafficRulesFactory.h>

#include <fstream>
#include <iostream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

using namespace lanelet;
using Json = nlohmann::json;

namespace {

struct Drive {
  std::string name;
  std::vector<BasicPoint2d> path;  // keyframe positions in the map's frame
};

Json readLsm(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
  const bool cbor = file.size() > 5 && file.substr(file.size() - 5) == ".cbor";
  return cbor ? Json::from_cbor(bytes) : Json::parse(bytes.begin(), bytes.end());
}

/// Unit direction of the lanelet's centre line near p.
BasicPoint2d axisAt(const ConstLanelet& ll, const BasicPoint2d& p) {
  const auto c = ll.centerline2d();
  std::size_t best = 0;
  double best_d = 1e300;
  for (std::size_t k = 0; k + 1 < c.size(); ++k) {
    const double d = (p - c[k].basicPoint2d()).norm() + (p - c[k + 1].basicPoint2d()).norm();
    if (d < best_d) best_d = d, best = k;
  }
  const BasicPoint2d d = (c[best + 1].basicPoint2d() - c[best].basicPoint2d());
  return d.norm() > 1e-9 ? BasicPoint2d(d.normalized()) : BasicPoint2d(1, 0);
}

/// The passable lanelet (oriented as driven) containing p with heading h; `previous` wins.
std::optional<ConstLanelet> laneletAt(LaneletMap& map, const traffic_rules::TrafficRules& rules,
                                      const BasicPoint2d& p, const BasicPoint2d& h,
                                      const std::optional<ConstLanelet>& previous) {
  std::optional<ConstLanelet> found;
  for (const auto& hit : geometry::findWithin2d(map.laneletLayer, p, 0.0)) {
    ConstLanelet ll = hit.second;
    if (axisAt(ll, p).dot(h) < 0) ll = ll.invert();
    if (!rules.canPass(ll)) continue;
    if (previous && previous->id() == ll.id() && previous->inverted() == ll.inverted()) return ll;
    if (!found) found = ll;
  }
  return found;
}

std::optional<Drive> readDrive(const std::string& file, const projection::UtmProjector* proj,
                               const Json& origin) {
  const Json lsm = readLsm(file);
  if (lsm.value("frame", "") != "enu") return std::nullopt;
  const Json& o = lsm.at("origin");
  GeographicLib::LocalCartesian enu(o.at("lat"), o.at("lon"), o.at("alt"));
  if (o != origin) return std::nullopt;
  Drive d;
  d.name = lsm.value("drive_id", file);
  for (const auto& k : lsm.at("keyframes")) {
    const auto& t = k.at("pose").at("t");
    double lat, lon, alt;
    enu.Reverse(t[0].get<double>(), t[1].get<double>(), t[2].get<double>(), lat, lon, alt);
    d.path.push_back(proj->forward(GPSPoint{lat, lon, alt}).head<2>());
  }
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: route_check MAP.osm LSM...\n";
    return 2;
  }
  Json origin;
  try {
    origin = readLsm(argv[2]).at("origin");
  } catch (const std::exception& e) {
    std::cerr << argv[2] << ": " << e.what() << "\n";
    return 3;
  }
  projection::UtmProjector proj(Origin({origin.at("lat"), origin.at("lon"), 0.0}));
  ErrorMessages errors;
  LaneletMapPtr map = load(argv[1], proj, &errors);
  if (!errors.empty()) {
    std::cerr << argv[1] << ": " << errors.size() << " load errors, first: " << errors[0] << "\n";
    return 3;
  }
  auto rules = traffic_rules::TrafficRulesFactory::create(Locations::Germany, Participants::Vehicle);
  auto graph = routing::RoutingGraph::build(*map, *rules);
  long total = 0, routed_total = 0;
  std::vector<std::string> unrouted;
  for (int a = 2; a < argc; ++a) {
    std::optional<Drive> d;
    try {
      d = readDrive(argv[a], &proj, origin);
    } catch (const std::exception& e) {
      std::cerr << argv[a] << ": " << e.what() << "\n";
      return 3;
    }
    if (!d) {
      std::cerr << argv[a] << ": not in ENU of the first LSM's origin\n";
      return 3;
    }
    std::vector<ConstLanelet> seq;
    std::optional<ConstLanelet> cur;
    int on = 0;
    for (std::size_t k = 0; k < d->path.size(); ++k) {
      const std::size_t j = k + 1 < d->path.size() ? k + 1 : k;
      const std::size_t i = j == k && k > 0 ? k - 1 : k;
      const BasicPoint2d h = d->path[j] - d->path[i];
      if (h.norm() < 1e-6) continue;
      const auto ll = laneletAt(*map, *rules, d->path[k], h.normalized(), cur);
      if (!ll) continue;
      ++on;
      if (!cur || cur->id() != ll->id() || cur->inverted() != ll->inverted()) seq.push_back(*ll);
      cur = ll;
    }
    int pairs = 0, routed = 0;
    for (std::size_t k = 0; k + 1 < seq.size(); ++k) {
      ++pairs;
      if (graph->shortestPath(seq[k], seq[k + 1])) {
        ++routed;
      } else {
        unrouted.push_back(d->name + ": " + std::to_string(seq[k].id()) + " -> " +
                           std::to_string(seq[k + 1].id()));
      }
    }
    total += pairs;
    routed_total += routed;
    std::cout << "drive " << d->name << ": keyframes=" << d->path.size() << " on_lanelets=" << on
              << " pairs=" << pairs << " routed=" << routed
              << " share=" << (pairs ? double(routed) / pairs : 1.0) << "\n";
  }
  std::cout << "total: pairs=" << total << " routed=" << routed_total
            << " share=" << (total ? double(routed_total) / total : 1.0) << "\n";
  for (std::size_t k = 0; k < unrouted.size() && k < 5; ++k)
    std::cout << "  no route: " << unrouted[k] << "\n";
  return 0;
}
