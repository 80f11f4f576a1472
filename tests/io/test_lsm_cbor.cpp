// The fast LSM CBOR codec (libmapfuse/src/io/lsm_cbor.hpp) against the general JSON-tree path:
// the same bytes out, the same LSM in, and every file it declines still judged by the general
// reader.
#include <catch2/catch.hpp>
#include <limits>
#include <random>

#include "fixtures.hpp"
#include "io/lsm_cbor.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "support/error_matchers.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {

std::string nlohmannBytes(const Lsm& lsm) {
  const std::vector<uint8_t> b = nlohmann::json::to_cbor(io::lsmToJson(lsm));
  return std::string(b.begin(), b.end());
}

// Bit-exact equality of everything an LSM holds.
void requireIdentical(const Lsm& a, const Lsm& b) {
  REQUIRE(a.drive_id == b.drive_id);
  REQUIRE(a.vehicle_id == b.vehicle_id);
  REQUIRE(a.frame == b.frame);
  REQUIRE(a.origin.has_value() == b.origin.has_value());
  if (a.origin) {
    CHECK(a.origin->lat == b.origin->lat);
    CHECK(a.origin->lon == b.origin->lon);
    CHECK(a.origin->alt == b.origin->alt);
  }
  REQUIRE(a.keyframes.size() == b.keyframes.size());
  for (std::size_t i = 0; i < a.keyframes.size(); ++i) {
    CHECK(a.keyframes[i].id == b.keyframes[i].id);
    CHECK(a.keyframes[i].stamp == b.keyframes[i].stamp);
    CHECK(a.keyframes[i].T_frame_body.matrix() == b.keyframes[i].T_frame_body.matrix());
    CHECK(a.keyframes[i].covariance == b.keyframes[i].covariance);
  }
  REQUIRE(a.gps.size() == b.gps.size());
  for (std::size_t i = 0; i < a.gps.size(); ++i) {
    CHECK(a.gps[i].stamp == b.gps[i].stamp);
    CHECK(a.gps[i].position.lat == b.gps[i].position.lat);
    CHECK(a.gps[i].position.lon == b.gps[i].position.lon);
    CHECK(a.gps[i].position.alt == b.gps[i].position.alt);
    CHECK(a.gps[i].sigma_h == b.gps[i].sigma_h);
    CHECK(a.gps[i].sigma_v == b.gps[i].sigma_v);
  }
  test::checkSameElements(a, b, 0.0);  // bit-exact
}

// Every encoding the writer can choose: small and large counts (1-, 2- and 4-byte lengths),
// negative and large integers, doubles that are and are not exact floats, optional fields.
Lsm bigLsm() {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n01;
  Lsm lsm = test::makeLsm();
  lsm.vehicle_id = "";
  for (int i = 3; i < 300; ++i) {
    Keyframe k;
    k.id = i * 100000;  // 4-byte integers
    k.stamp = 1.0 + 0.1 * i;
    k.T_frame_body =
        poseFromXyzRpy(10.0 * i + n01(rng), n01(rng), 0.25, 0.01 * n01(rng), 0, 3 * n01(rng));
    k.covariance = diagonalCovariance(0.5, 0.25);  // exact floats
    lsm.keyframes.push_back(k);
  }
  for (int i = 0; i < 70000; ++i)  // 4-byte array length
    lsm.gps.push_back({double(i), {49.0 + 1e-6 * i, 8.4, 100.0 + i}, 1.0 + 1e-3 * i, 2.0});
  Element e = lsm.elements[0];
  e.points_body.clear();
  e.covariances.clear();
  for (int i = 0; i < 300; ++i) {                                // 2-byte array length
    e.points_body.push_back({n01(rng), -1.5, 10.0 * n01(rng)});  // within the element bounds
    e.covariances.push_back(Eigen::Vector3d(0.01, 0.02, 0.0).asDiagonal());  // PSD, singular
  }
  e.id = -123456789;
  e.anchor = 299 * 100000;
  e.truth_id = 0;
  e.observations = 70000;
  e.height = 0.5;
  lsm.elements.push_back(e);
  return lsm;
}

}  // namespace

TEST_CASE("the fast LSM CBOR writer gives nlohmann's bytes", "[io][lsm][cbor]") {
  for (const Lsm& lsm : {test::makeLsm(), bigLsm()}) {
    const std::string ours = io::detail::encodeLsmCbor(lsm);
    const std::string theirs = nlohmannBytes(lsm);
    REQUIRE(ours.size() == theirs.size());
    CHECK(ours == theirs);
  }
  Lsm odom = test::makeLsm();  // no origin, odom frame
  odom.frame = LsmFrame::kOdom;
  odom.origin.reset();
  CHECK(io::detail::encodeLsmCbor(odom) == nlohmannBytes(odom));
}

TEST_CASE("the fast LSM CBOR reader gives the general reader's LSM", "[io][lsm][cbor]") {
  const auto dir = test::tempDir("lsm-cbor-fast");
  for (const Lsm& lsm : {test::makeLsm(), bigLsm()}) {
    const std::string bytes = nlohmannBytes(lsm);
    const std::optional<Lsm> fast = io::detail::decodeLsmCbor(bytes);
    REQUIRE(fast.has_value());  // the fast path takes canonical files
    const Lsm general =
        io::lsmFromJson(nlohmann::json::from_cbor(bytes.begin(), bytes.end()), "x.cbor");
    requireIdentical(*fast, general);
    io::writeLsm(dir / "a.lsm.cbor", lsm);
    requireIdentical(io::readLsm(dir / "a.lsm.cbor"), general);
  }
}

TEST_CASE("CBOR the fast reader declines is still read or refused as before", "[io][lsm][cbor]") {
  const auto dir = test::tempDir("lsm-cbor-decline");
  const Lsm lsm = test::makeLsm();
  SECTION("per-point sigmas instead of covariances: declined, read by the general path") {
    io::Json d = io::lsmToJson(lsm);
    d["elements"][1].erase("cov");
    d["elements"][1]["sigma"] = {0.2};
    const std::vector<uint8_t> b = nlohmann::json::to_cbor(d);
    CHECK_FALSE(io::detail::decodeLsmCbor(std::string(b.begin(), b.end())).has_value());
    io::writeDocument(dir / "s.cbor", d);
    const Lsm read = io::readLsm(dir / "s.cbor");
    CHECK(read.elements[1].covariances[0].isApprox(Eigen::Matrix3d::Identity() * 0.04));
  }
  SECTION("a covariance that is not PSD: declined, refused with its field") {
    io::Json d = io::lsmToJson(lsm);
    d["elements"][0]["cov"][2] = {0.01, 0.5, 0.0, 0.01, 0.0, 0.01};
    io::writeDocument(dir / "p.cbor", d);
    CHECK_THROWS_MATCHES(io::readLsm(dir / "p.cbor"), ParseError,
                         test::ParseErrorAt("elements[0].cov[2]", "", "positive semi-definite"));
  }
  SECTION("a null optional field counts as absent, as in JSON") {
    io::Json d = io::lsmToJson(lsm);
    d["elements"][1]["height"] = nullptr;
    io::writeDocument(dir / "n.cbor", d);
    CHECK(io::readLsm(dir / "n.cbor").elements[1].height == 0.0);
  }
  SECTION("values out of range are left to the general reader") {
    // an observation count that wraps when narrowed to int (2^32 + 1 would read as 1)
    io::Json d = io::lsmToJson(lsm);
    d["elements"][0]["observations"] = (int64_t(1) << 32) + 1;
    std::vector<uint8_t> b = nlohmann::json::to_cbor(d);
    CHECK_FALSE(io::detail::decodeLsmCbor(std::string(b.begin(), b.end())).has_value());
    // a keyframe 1e8 m from the origin, an element point 1e5 m from its anchor
    d = io::lsmToJson(lsm);
    d["keyframes"][0]["pose"]["t"] = {1e8, 0.0, 0.0};
    b = nlohmann::json::to_cbor(d);
    CHECK_FALSE(io::detail::decodeLsmCbor(std::string(b.begin(), b.end())).has_value());
    d = io::lsmToJson(lsm);
    d["elements"][0]["points"][0] = {0.0, 1e5, 0.0};
    b = nlohmann::json::to_cbor(d);
    CHECK_FALSE(io::detail::decodeLsmCbor(std::string(b.begin(), b.end())).has_value());
    // just inside the bounds the fast path still reads
    d = io::lsmToJson(lsm);
    d["elements"][0]["observations"] = std::numeric_limits<int>::max();
    b = nlohmann::json::to_cbor(d);
    const auto fast = io::detail::decodeLsmCbor(std::string(b.begin(), b.end()));
    REQUIRE(fast.has_value());
    CHECK(fast->elements[0].observations == std::numeric_limits<int>::max());
  }
  SECTION("trailing bytes after the LSM") {
    std::string bytes = nlohmannBytes(lsm);
    CHECK(io::detail::decodeLsmCbor(bytes).has_value());
    bytes.push_back('\0');
    CHECK_FALSE(io::detail::decodeLsmCbor(bytes).has_value());
    test::writeText(dir / "t.cbor", bytes);
    CHECK_THROWS_AS(io::readLsm(dir / "t.cbor"), ParseError);
  }
}

TEST_CASE("a CBOR LSM outside the readers' bounds is refused as the JSON reader refuses it",
          "[io][lsm][cbor][bounds]") {
  // The fast codec decodes numbers it does not judge; readLsm then checks the bounds of
  // docs/formats.md and lets the general reader refuse the file naming the field.
  const auto dir = test::tempDir("lsm-cbor-bounds");
  Lsm lsm = test::makeLsm();
  REQUIRE(lsm.keyframes.size() >= 2);
  lsm.keyframes[1].T_frame_body.translation().x() += 5000.0;  // a jump no drive makes
  const std::string bytes = nlohmannBytes(lsm);
  REQUIRE(io::detail::decodeLsmCbor(bytes).has_value());  // the codec alone accepts it
  io::writeBytesAtomic(dir / "jump.lsm.cbor", bytes);
  CHECK_THROWS_WITH(io::readLsm(dir / "jump.lsm.cbor"),
                    Catch::Contains("jump.lsm.cbor") && Catch::Contains("keyframes[1]"));
  lsm = test::makeLsm();
  lsm.gps.front().sigma_h = 0.0;
  io::writeBytesAtomic(dir / "sigma.lsm.cbor", nlohmannBytes(lsm));
  CHECK_THROWS_WITH(io::readLsm(dir / "sigma.lsm.cbor"), Catch::Contains("sigma_h"));
}
