#include <catch2/catch.hpp>

#include "fixtures.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "support/error_matchers.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
constexpr double kExact = 1e-12;  // JSON keeps doubles to round-trip precision

void requireSameLsm(const Lsm& a, const Lsm& b) {
  REQUIRE(a.drive_id == b.drive_id);
  REQUIRE(a.vehicle_id == b.vehicle_id);
  REQUIRE(a.frame == b.frame);
  REQUIRE(a.origin.has_value() == b.origin.has_value());
  CHECK(a.origin->lat == b.origin->lat);
  REQUIRE(a.keyframes.size() == b.keyframes.size());
  for (std::size_t i = 0; i < a.keyframes.size(); ++i) {
    CHECK(a.keyframes[i].id == b.keyframes[i].id);
    CHECK((a.keyframes[i].T_frame_body.matrix() - b.keyframes[i].T_frame_body.matrix()).norm() <
          kExact);
    CHECK((a.keyframes[i].covariance - b.keyframes[i].covariance).norm() < kExact);
  }
  REQUIRE(a.gps.size() == b.gps.size());
  CHECK(a.gps[0].position.lon == b.gps[0].position.lon);
  CHECK(a.gps[0].sigma_v == b.gps[0].sigma_v);
  test::checkSameElements(a, b, kExact);
}

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("LSM round-trips through JSON and CBOR", "[io][lsm]") {
  const auto dir = test::tempDir("lsm-roundtrip");
  const Lsm lsm = test::makeLsm();
  for (const char* name : {"a.json", "a.cbor"}) {
    io::writeLsm(dir / name, lsm);
    requireSameLsm(lsm, io::readLsm(dir / name));
  }
  // CBOR is the compact encoding.
  CHECK(std::filesystem::file_size(dir / "a.cbor") < std::filesystem::file_size(dir / "a.json"));
}

TEST_CASE("element points move rigidly with their anchor keyframe", "[io][lsm]") {
  Lsm lsm = test::makeLsm();
  const auto before = lsm.pointsInFrame(lsm.elements[0]);
  const Pose3 delta = poseFromXyzRpy(1, 2, 0, 0, 0, 0.3);
  lsm.keyframes[1].T_frame_body = delta * lsm.keyframes[1].T_frame_body;
  const auto after = lsm.pointsInFrame(lsm.elements[0]);
  for (std::size_t i = 0; i < before.size(); ++i)
    CHECK((after[i] - delta * before[i]).norm() < kExact);
}

TEST_CASE("malformed LSM files are refused with file, field and problem", "[io][lsm]") {
  const auto dir = test::tempDir("lsm-malformed");
  const auto good = io::lsmToJson(test::makeLsm());
  // JSON, and CBOR (where the fast codec declines the file and the general reader judges it).
  auto expectParseError = [&](io::Json doc, const std::string& field, const std::string& problem) {
    for (const char* name : {"bad.json", "bad.cbor"}) {
      const auto path = dir / name;
      io::writeDocument(path, doc);
      try {
        io::readLsm(path);
        FAIL("accepted a malformed LSM, expected an error at " << field);
      } catch (const ParseError& e) {
        CHECK(e.file() == path.string());
        CHECK(e.field() == field);
        CHECK_THAT(e.problem(), Catch::Contains(problem));
        CHECK(e.exitCode() == ExitCode::kBadInput);
      }
    }
  };
  // Each case damages one field of a good LSM.
  struct Case {
    const char* what;
    void (*damage)(io::Json&);
    const char* field;
    const char* problem;
  };
  const Case cases[] = {
      {"missing field", [](io::Json& d) { d["elements"][0].erase("anchor"); }, "elements[0].anchor",
       "missing"},
      {"wrong type", [](io::Json& d) { d["keyframes"][1]["stamp"] = "noon"; }, "keyframes[1].stamp",
       "expected a number"},
      {"unknown key", [](io::Json& d) { d["elements"][1]["colour"] = "white"; },
       "elements[1].colour", "unknown key"},
      {"unknown class", [](io::Json& d) { d["elements"][0]["class"] = "lane"; },
       "elements[0].class", "unknown class"},
      {"wrong format tag", [](io::Json& d) { d["format"] = "mapfuse.vector_map"; }, "format",
       "expected \"mapfuse.lsm\""},
      {"wrong version", [](io::Json& d) { d["version"] = 99; }, "version", "unsupported version"},
      {"non-unit quaternion",
       [](io::Json& d) {
         d["keyframes"][0]["pose"]["q"] = {2.0, 0.0, 0.0, 0.0};
       },
       "keyframes[0].pose.q", "quaternion norm"},
      {"covariance count differs from point count",
       [](io::Json& d) { d["elements"][0]["cov"].erase(0); }, "elements[0].cov",
       "one covariance per point"},
      {"enu without origin", [](io::Json& d) { d.erase("origin"); }, "origin", "missing"},
  };
  for (const Case& c : cases) {
    INFO(c.what);
    auto d = good;
    c.damage(d);
    expectParseError(d, c.field, c.problem);
  }
}

TEST_CASE("NaN and Inf are refused", "[io][lsm]") {
  const auto dir = test::tempDir("lsm-nan");
  auto d = io::lsmToJson(test::makeLsm());
  d["elements"][0]["points"][1][0] = std::numeric_limits<double>::infinity();
  // CBOR can carry Inf/NaN (JSON text cannot): the reader must catch it.
  io::writeDocument(dir / "inf.cbor", d);
  CHECK_THROWS_MATCHES(io::readLsm(dir / "inf.cbor"), ParseError,
                       test::ParseErrorAt("elements[0].points[1][0]", "", "not finite"));
  test::writeText(dir / "nan.json", R"({"format": "mapfuse.lsm", "version": 1, "x": NaN})");
  CHECK_THROWS_AS(io::readLsm(dir / "nan.json"), ParseError);
}

TEST_CASE("truncated and empty files are refused, not crashed on", "[io][lsm]") {
  const auto dir = test::tempDir("lsm-truncated");
  io::writeLsm(dir / "full.json", test::makeLsm());
  io::writeLsm(dir / "full.cbor", test::makeLsm());
  for (const char* name : {"full.json", "full.cbor"}) {
    const std::string bytes = test::readText(dir / name);
    const auto cut = dir / (std::string("cut") + std::filesystem::path(name).extension().string());
    test::writeText(cut, bytes.substr(0, bytes.size() / 2));
    const std::string msg = messageOf([&] { io::readLsm(cut); });
    CHECK_THAT(msg, Catch::Contains(cut.string()));
    CHECK_THROWS_AS(io::readLsm(cut), ParseError);
  }
  test::writeText(dir / "empty.json", "");
  CHECK_THROWS_AS(io::readLsm(dir / "empty.json"), ParseError);
  CHECK_THROWS_AS(io::readLsm(dir / "absent.json"), IoError);
  CHECK_THROWS_AS(io::readLsm(dir / "full.txt"), IoError);  // unknown extension
}

TEST_CASE("inconsistent LSM content is refused as bad input", "[io][lsm]") {
  const auto dir = test::tempDir("lsm-inconsistent");
  auto d = io::lsmToJson(test::makeLsm());
  d["elements"][0]["anchor"] = 77;
  io::writeDocument(dir / "a.json", d);
  const std::string msg = messageOf([&] { io::readLsm(dir / "a.json"); });
  CHECK_THAT(msg, Catch::Contains("elements[0].anchor 77"));
  CHECK_THROWS_AS(io::readLsm(dir / "a.json"), InputError);
}

TEST_CASE("info describes files and derives the batch origin", "[io][info]") {
  const auto dir = test::tempDir("info");
  Lsm lsm = test::makeLsm();
  io::writeLsm(dir / "enu.json", lsm);
  const std::string info = test::appPath("info").string();
  REQUIRE(test::runCommand(info + " " + (dir / "enu.json").string() + " > " +
                           (dir / "out.txt").string()) == 0);
  const auto j = io::Json::parse(test::readText(dir / "out.txt"));
  CHECK(j["format"] == "mapfuse.lsm");
  CHECK(j["elements"] == 2);
  CHECK(j["keyframes"] == 3);
  CHECK(j["trajectory_length_m"].get<double>() == Approx(10.0).epsilon(0.01));
  // An odom LSM: the origin is its first GPS fix.
  lsm.frame = LsmFrame::kOdom;
  lsm.origin.reset();
  io::writeLsm(dir / "odom.cbor", lsm);
  REQUIRE(test::runCommand(info + " --origin " + (dir / "odom.cbor").string() + " > " +
                           (dir / "o.txt").string()) == 0);
  CHECK(test::readText(dir / "o.txt") == "49.011,8.4228,113\n");
  lsm.gps.clear();
  io::writeLsm(dir / "nogps.json", lsm);
  CHECK(test::runCommand(info + " --origin " + (dir / "nogps.json").string() + " 2>/dev/null") ==
        3);
  test::writeText(dir / "junk.json", "{\"format\": 3}");
  CHECK(test::runCommand(info + " " + (dir / "junk.json").string() + " 2>/dev/null") == 3);
}
