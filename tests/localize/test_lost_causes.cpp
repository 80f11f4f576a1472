// localize/lost_causes.hpp (issue 35): a lost keyframe that observed fewer points than
// min_matches is "no markings to match", one that observed enough is "outside the map"; the
// diagnosis names the drive (its file), not the map.
#include <catch2/catch.hpp>

#include "mapfuse/localize/lost_causes.hpp"

using namespace mapfuse;
using namespace mapfuse::localize;

namespace {
KeyframeLocalization keyframe(bool lost, int observed) {
  KeyframeLocalization k;
  k.status = lost ? KeyframeStatus::kLost : KeyframeStatus::kOk;
  k.observed = observed;
  return k;
}
}  // namespace

TEST_CASE("lost keyframes are split into no markings and outside the map", "[localize]") {
  const int min_matches = 10;
  LocalizeResult r;
  r.keyframes = {keyframe(false, 50), keyframe(true, 0),  keyframe(true, 9),
                 keyframe(true, 10),  keyframe(true, 40), keyframe(false, 12)};
  r.lost = 4;
  const LostCauses c = lostCauses(r, min_matches);
  CHECK(c.no_markings == 2);  // 0 and 9 observed points: below min_matches
  CHECK(c.outside_map == 2);  // 10 and 40: enough to match, the map did not hold them

  LocalizeResult clean;
  clean.keyframes = {keyframe(false, 30)};
  const std::string why =
      lostDiagnosis({{"drives/a.cbor", &r}, {"drives/b.cbor", &clean}}, min_matches);
  CHECK(why.find("drives/a.cbor: 4 of 6 keyframes lost (2 no markings to match") == 0);
  CHECK(why.find("; 2 outside the map") != std::string::npos);
  CHECK(why.find("drives/b.cbor") == std::string::npos);  // nothing lost: not named
}
