#include <sys/wait.h>
#include <unistd.h>
#include <catch2/catch.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
bool hasTempFiles(const std::filesystem::path& dir) {
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().string().find(".tmp-") != std::string::npos) return true;
  return false;
}
}  // namespace

TEST_CASE("a write that fails mid-way leaves the previous file intact", "[io][atomic]") {
  const auto dir = test::tempDir("atomic-throw");
  const auto path = dir / "out.json";
  io::writeBytesAtomic(path, "previous content");
  CHECK_THROWS_AS(io::writeFileAtomic(path,
                                      [](std::ostream& out) {
                                        out << "half of the new con";
                                        throw InputError("stage failed");
                                      }),
                  InputError);
  CHECK(test::readText(path) == "previous content");
  CHECK_FALSE(hasTempFiles(dir));
}

TEST_CASE("a process killed mid-write leaves the previous file intact", "[io][atomic]") {
  const auto dir = test::tempDir("atomic-kill");
  const auto path = dir / "out.bin";
  io::writeBytesAtomic(path, "previous content");
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    io::writeFileAtomic(path, [](std::ostream& out) {
      out << std::string(1 << 20, 'x');
      out.flush();
      ::_exit(9);  // dies before the rename, like a killed process
    });
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  REQUIRE(WIFEXITED(status));
  REQUIRE(WEXITSTATUS(status) == 9);
  CHECK(test::readText(path) == "previous content");
}

TEST_CASE("atomic writes create folders and report unwritable places", "[io][atomic]") {
  const auto dir = test::tempDir("atomic-dirs");
  io::writeBytesAtomic(dir / "a" / "b" / "c.txt", "x");
  CHECK(test::readText(dir / "a" / "b" / "c.txt") == "x");
  test::writeText(dir / "file", "not a folder");
  try {
    io::writeBytesAtomic(dir / "file" / "c.txt", "x");
    FAIL("wrote below a file");
  } catch (const IoError& e) {
    CHECK(e.exitCode() == ExitCode::kIo);
  }
  CHECK_THROWS_AS(io::readBytes(dir / "missing"), IoError);
  CHECK_THROWS_AS(io::readBytes(dir), IoError);
}
