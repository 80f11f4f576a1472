// Readers refuse values outside docs/formats.md "Value bounds" with a ParseError naming the file
// and field, instead of crashing, hanging or passing absurd values on (issue 19). Each case is
// an input that crashed, hung, wrapped or went through before the bounds.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "fixtures.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/io/align_registrations.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/drive_frames.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/tiles_manifest.hpp"
#include "mapfuse/io/vector_map_io.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
using Catch::Contains;

namespace {

Lsm parseLsm(const io::Json& doc) {
  return io::lsmFromJson(doc, "t.lsm.json");
}
VectorMap parseMap(const io::Json& doc) {
  return io::vectorMapFromJson(doc, "t.map.json");
}

}  // namespace

TEST_CASE("CBOR and JSON nested deeper than the limit are a ParseError, not a stack overflow",
          "[io][bounds]") {
  // 500 KB of one-element CBOR arrays segfaulted `info` (recursive descent).
  const std::string deep_cbor = std::string(500000, '\x81') + std::string(1, '\0');
  CHECK_THROWS_WITH(io::parseDocument(deep_cbor, io::Encoding::kCbor, "deep.cbor"),
                    Contains("deep.cbor") && Contains("nested deeper than 64"));
  const std::string deep_json = std::string(200000, '[') + std::string(200000, ']');
  CHECK_THROWS_AS(io::parseDocument(deep_json, io::Encoding::kJson, "deep.json"), ParseError);
  // The limit itself is fine: 64 levels parse, 65 do not.
  CHECK(io::parseDocument(std::string(64, '[') + std::string(64, ']'), io::Encoding::kJson, "ok")
            .is_array());
  CHECK_THROWS_AS(
      io::parseDocument(std::string(65, '[') + std::string(65, ']'), io::Encoding::kJson, "x"),
      ParseError);
  CHECK_THROWS_WITH(io::parseDocument("", io::Encoding::kCbor, "empty.cbor"),
                    Contains("file is empty"));
}

TEST_CASE("CBOR text that is not UTF-8 is a ParseError, through both LSM readers",
          "[io][bounds][lsm]") {
  // fuzz_lsm (10-minute run of 2026-11-25): a CBOR LSM whose drive_id held the byte 0xFF was
  // accepted, then writing it as JSON threw (info: exit 1 "internal error"; georef: exit 0).
  Lsm lsm = test::makeLsm();
  lsm.drive_id = "drive-\xFF";
  const io::Json doc = io::lsmToJson(lsm);
  const std::vector<uint8_t> cbor = io::Json::to_cbor(doc);
  const std::string bytes(cbor.begin(), cbor.end());
  CHECK_THROWS_WITH(io::parseDocument(bytes, io::Encoding::kCbor, "bad.lsm.cbor"),
                    Contains("bad.lsm.cbor") && Contains("not valid UTF-8"));
  // The fast CBOR decoder of readLsm declines it, and the generic reader names the problem.
  const auto dir = test::tempDir("utf8_lsm");
  io::writeBytesAtomic(dir / "bad.lsm.cbor", bytes);
  CHECK_THROWS_WITH(io::readLsm(dir / "bad.lsm.cbor"), Contains("not valid UTF-8"));
  // Well-formed multi-byte text passes; overlong forms, surrogates and truncation do not.
  lsm.drive_id =
      "stra\xC3\x9F"
      "e-\xE2\x82\xAC-\xF0\x9F\x9A\x97";
  const std::vector<uint8_t> ok = io::Json::to_cbor(io::lsmToJson(lsm));
  CHECK(io::lsmFromJson(
            io::parseDocument(std::string(ok.begin(), ok.end()), io::Encoding::kCbor, "ok.cbor"),
            "ok.cbor")
            .drive_id == lsm.drive_id);
  for (const std::string bad : {"\xC0\xAF", "\xED\xA0\x80", "\xF4\x90\x80\x80", "\xE2\x82"}) {
    io::Json j = io::Json::object();
    j[std::string("k")] = "x";
    std::vector<uint8_t> c = io::Json::to_cbor(j);  // {"k": "x"}: a1 61 6b 61 78
    std::string b(c.begin(), c.end() - 2);
    b += char(0x60 + bad.size());
    b += bad;
    CHECK_THROWS_AS(io::parseDocument(b, io::Encoding::kCbor, "t.cbor"), ParseError);
  }
}

TEST_CASE("the LSM reader refuses coordinates, stamps, sigmas and counts outside the bounds",
          "[io][bounds][lsm]") {
  const io::Json good = io::lsmToJson(test::makeLsm());
  REQUIRE_NOTHROW(parseLsm(good));

  io::Json doc = good;
  doc["keyframes"][0]["pose"]["t"][0] = 1e308;  // went through georef and align with exit 0
  CHECK_THROWS_WITH(parseLsm(doc), Contains("keyframes[0].pose.t[0]") && Contains("outside"));

  doc = good;
  doc["elements"][0]["points"][1][0] = 1e8;  // aggregate allocated 5.7 GB
  CHECK_THROWS_WITH(parseLsm(doc), Contains("elements[0].points[1][0]"));

  doc = good;  // 1e4 m away is within range, but a polyline back and forth is too long
  doc["elements"][0]["points"] = {{9000, 0, 0}, {-9000, 0, 0}, {9000, 0, 0}};
  CHECK_THROWS_WITH(parseLsm(doc), Contains("elements[0].points") && Contains("m long"));

  doc = good;  // a keyframe 14,000 km from its neighbours, 0.5 s later
  doc["keyframes"][1]["pose"]["t"] = {1e7, -1e7, 0.0};
  CHECK_THROWS_WITH(parseLsm(doc), Contains("keyframes[1].pose") && Contains("previous one"));

  doc = good;  // wrapped to 5 when narrowed to int
  doc["elements"][0]["observations"] = 4294967301LL;
  CHECK_THROWS_WITH(parseLsm(doc), Contains("elements[0].observations") && Contains("outside"));

  doc = good;  // an unsigned integer beyond int64 wrapped to -1
  doc["elements"][0]["id"] = std::numeric_limits<uint64_t>::max();
  CHECK_THROWS_WITH(parseLsm(doc), Contains("elements[0].id") && Contains("too large"));

  doc = good;
  doc["keyframes"][0]["stamp"] = 1e300;
  CHECK_THROWS_WITH(parseLsm(doc), Contains("keyframes[0].stamp"));
  doc = good;
  doc["gps"][0]["alt"] = 1e9;
  CHECK_THROWS_WITH(parseLsm(doc), Contains("gps[0].alt"));
  doc = good;
  doc["gps"][0]["sigma_h"] = 1e200;
  CHECK_THROWS_WITH(parseLsm(doc), Contains("gps[0].sigma_h"));
  doc = good;
  doc["elements"][1]["height"] = -4.5;
  CHECK_THROWS_WITH(parseLsm(doc), Contains("elements[1].height"));

  // CBOR can hold NaN and infinity, which JSON text cannot: refused as not finite.
  doc = good;
  doc["keyframes"][0]["pose"]["t"][1] = std::numeric_limits<double>::quiet_NaN();
  const std::vector<uint8_t> cbor = io::Json::to_cbor(doc);
  CHECK_THROWS_WITH(io::lsmFromJson(io::parseDocument(std::string(cbor.begin(), cbor.end()),
                                                      io::Encoding::kCbor, "nan.cbor"),
                                    "nan.cbor"),
                    Contains("keyframes[0].pose.t[1]") && Contains("not finite"));
}

TEST_CASE("the vector map reader refuses overflowing integer coordinates and absurd chains",
          "[io][bounds][vector_map]") {
  io::VectorMapWriteOptions compact;
  compact.compact = true;
  compact.coordinate_quantum = 1.0 / 256;
  const io::Json good = io::vectorMapToJson(test::makeVectorMap(), compact);
  REQUIRE_NOTHROW(parseMap(good));
  REQUIRE(good["instances"][1].contains("points_q"));

  io::Json doc = good;  // the running sum overflowed int64 (undefined behaviour)
  const int64_t big = std::numeric_limits<int64_t>::max();
  doc["instances"][1]["points_q"] = {big, 0, 0, big, 0, 0, big, 0, 0};
  CHECK_THROWS_WITH(parseMap(doc), Contains("instances[1].points_q[0]") && Contains("leaves"));

  doc = good;  // a quantum of 1e-300 m made every coordinate INT64_MIN when written
  doc["quantum"] = 1e-300;
  CHECK_THROWS_WITH(parseMap(doc), Contains("field 'quantum'"));

  doc = io::vectorMapToJson(test::makeVectorMap());
  doc["instances"][0].erase("points");  // readers sample the chain every 0.5 m
  doc["instances"][0]["bezier"] = {{{0, 0, 0}, {9e6, 0, 0}, {-9e6, 0, 0}, {9e6, 0, 0}}};
  CHECK_THROWS_WITH(parseMap(doc), Contains("instances[0].bezier") && Contains("long"));

  doc = io::vectorMapToJson(test::makeVectorMap());
  doc["instances"][0]["class"] = "pole";  // a chain on a point element
  CHECK_THROWS_WITH(parseMap(doc), Contains("instances[0].class") && Contains("Bezier"));

  doc = io::vectorMapToJson(test::makeVectorMap());
  doc["instances"][0]["support"]["drives"] = 4294967297LL;  // was 1 after narrowing
  CHECK_THROWS_WITH(parseMap(doc), Contains("instances[0].support.drives"));
}

TEST_CASE("tiles.json: folder names and LSM paths stay below the manifest, no duplicates",
          "[io][bounds][tiles]") {
  const io::Json good = {
      {"format", "mapfuse.tiles"},
      {"version", 1},
      {"tile_size", 100.0},
      {"margin", 20.0},
      {"tiles",
       {{{"name", "tile_0_0"},
         {"ix", 0},
         {"iy", 0},
         {"core", {0, 0, 100, 100}},
         {"lsms", {"tile_0_0/a.cbor"}}},
        {{"name", "tile_m1_0"}, {"ix", -1}, {"iy", 0}, {"lsms", {"tile_m1_0/a.cbor"}}}}}};
  const io::TilesManifest m = io::tilesManifestFromJson(good, "tiles.json");
  REQUIRE(m.tiles.size() == 2);
  CHECK(m.tiles[1].ix == -1);
  CHECK(m.tiles[1].lsms == std::vector<std::string>{"tile_m1_0/a.cbor"});

  auto refuses = [&](io::Json doc, const std::string& field) {
    CHECK_THROWS_WITH(io::tilesManifestFromJson(doc, "tiles.json"),
                      Contains("tiles.json") && Contains(field));
  };
  io::Json doc = good;
  doc["tiles"][1]["name"] = "tile_0_0";  // two tiles with one name went through
  refuses(doc, "tiles[1].name");
  doc = good;
  doc["tiles"][0]["name"] = "../../elsewhere";  // balance writes <out>/<name>/...
  refuses(doc, "tiles[0].name");
  doc = good;
  doc["tiles"][0]["lsms"][0] = "/etc/passwd";
  refuses(doc, "tiles[0].lsms[0]");
  doc = good;
  doc["tiles"][0]["lsms"][0] = "tile_0_0/../../x.cbor";
  refuses(doc, "tiles[0].lsms[0]");
  doc = good;
  doc["tiles"][0]["lsms"][0] = "tile_0_0/" + std::string(300, 'a') + ".cbor";  // > NAME_MAX
  refuses(doc, "tiles[0].lsms[0]");
  doc = good;
  doc["tiles"][0]["name"] = std::string(300, 't');
  refuses(doc, "tiles[0].name");
  doc = good;
  doc["tiles"][1]["ix"] = 0;
  refuses(doc, "tiles[1].iy");
  doc = good;
  doc["tile_size"] = 1e-300;
  refuses(doc, "tile_size");
  doc = good;
  doc["margin"] = 60.0;
  refuses(doc, "margin");
}

TEST_CASE("a drive folder naming files the file system cannot hold is bad input, not a crash",
          "[io][bounds]") {
  // fuzz_drive_frames (CI's 20 s pass): a 2 KB calibration name made std::filesystem::exists
  // throw "File name too long" out of the reader, an uncaught exception.
  const auto dir = test::tempDir("drive_long_names");
  const io::Json frames = {{"format", io::kFramesFormat},
                           {"version", 1},
                           {"drive_id", "d"},
                           {"calibration", std::string(2000, 'c')},
                           {"imu", "imu.csv"},
                           {"wheel", "wheel.csv"},
                           {"frames", "frames.csv"}};
  test::writeText(dir / "frames.json", frames.dump());
  CHECK_THROWS_WITH(io::readDriveFrames(dir), Contains("frames.json") && Contains("calibration") &&
                                                  Contains("2000 bytes long"));
  io::Json escape = frames;
  escape["calibration"] = "../calibration.json";  // the folder's files stay in the folder
  test::writeText(dir / "frames.json", escape.dump());
  CHECK_THROWS_WITH(io::readDriveFrames(dir),
                    Contains("calibration") && Contains("not a path below the folder"));
  // A name below a regular file: missing, an IoError (exit 4), not std::filesystem's error.
  io::Json under_file = frames;
  under_file["calibration"] = "frames.json/calibration.json";
  test::writeText(dir / "frames.json", under_file.dump());
  CHECK_THROWS_AS(io::readDriveFrames(dir), IoError);
}

TEST_CASE("align summary: registrations name inputs that exist", "[io][bounds][tiles]") {
  const io::Json doc = {{"stage", "align"},
                        {"inputs", {"a.cbor", "b.cbor"}},
                        {"pairs",
                         {{{"lsm_a", 0},
                           {"lsm_b", 1},
                           {"accepted", true},
                           {"pcm_consistent", true},
                           {"graph_outlier", false}},
                          {{"lsm_a", 1}, {"lsm_b", 0}, {"accepted", false}}}}};
  const io::AlignRegistrations r = io::alignRegistrationsFromJson(doc, "align.summary.json");
  REQUIRE(r.pairs.size() == 2);
  CHECK(r.pairs[0].kept);
  CHECK_FALSE(r.pairs[1].kept);
  io::Json bad = doc;
  bad["pairs"][1]["lsm_b"] = 2;
  CHECK_THROWS_WITH(io::alignRegistrationsFromJson(bad, "align.summary.json"),
                    Contains("pairs[1]") && Contains("lsm_a / lsm_b"));
}
