#include "mapfuse/aggregate/observations.hpp"

#include <cmath>
#include <sstream>

#include "mapfuse/core/error.hpp"

namespace mapfuse::aggregate {

namespace {
std::string describe(const geo::GeoOrigin& o) {
  std::ostringstream s;
  s.precision(10);
  s << "(lat " << o.lat << ", lon " << o.lon << ", alt " << o.alt << ")";
  return s.str();
}
}  // namespace

ObservationSet collectObservations(const std::vector<Lsm>& lsms,
                                   const std::vector<std::string>& sources) {
  if (lsms.empty()) throw InputError("no input LSM");
  if (sources.size() != lsms.size()) throw InputError("one source name per LSM is required");
  ObservationSet set;
  set.num_drives = int(lsms.size());
  for (std::size_t d = 0; d < lsms.size(); ++d) {
    const Lsm& lsm = lsms[d];
    if (lsm.frame != LsmFrame::kEnu || !lsm.origin)
      throw InputError(sources[d] +
                       ": LSM is in frame 'odom'; aggregate needs georeferenced LSMs (frame 'enu', "
                       "run georef or align first)");
    if (d == 0) {
      set.origin = *lsm.origin;
    } else if (!geo::sameOrigin(set.origin, *lsm.origin)) {
      throw InputError(sources[d] + ": origin " + describe(*lsm.origin) + " differs from " +
                       sources[0] + " origin " + describe(set.origin) +
                       "; all LSMs must share one ENU origin");
    }
    for (const Element& e : lsm.elements) {
      Observation o;
      o.drive = int(d);
      o.element_id = e.id;
      o.cls = e.cls;
      o.attributes = e.attributes;
      o.points = lsm.pointsInFrame(e);
      o.confidence = e.confidence;
      o.observations = e.observations;
      o.height = e.height;
      o.truth_id = e.truth_id;
      set.items.push_back(std::move(o));
    }
  }
  return set;
}

std::vector<std::size_t> indicesOfClass(const ObservationSet& set, CrowdClass cls) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < set.items.size(); ++i)
    if (set.items[i].cls == cls) out.push_back(i);
  return out;
}

}  // namespace mapfuse::aggregate
