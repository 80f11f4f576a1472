// A run's outputs are replaced as a set: staged, then committed in write order, or left as they
// were when the run fails; the output folder is locked and stale temporary files are removed.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <stdexcept>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
namespace fs = std::filesystem;

namespace {
std::size_t temporaries(const fs::path& dir) {
  std::size_t n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    n += e.path().filename().string().find(".tmp-") != std::string::npos;
  return n;
}

/// The pid of a process that has ended.
pid_t deadPid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}
}  // namespace

TEST_CASE("a committed transaction replaces every output, in write order", "[io][output]") {
  const auto dir = test::tempDir("tx-commit");
  io::writeBytesAtomic(dir / "map.json", "old map");
  {
    io::OutputTransaction tx(dir);
    io::writeBytesAtomic(dir / "map.json", "new map");
    io::writeBytesAtomic(dir / "sub" / "labels.bin", "labels");
    io::writeBytesAtomic(dir / "stage.summary.json", "summary");
    // nothing is replaced before the commit
    CHECK(io::readBytes(dir / "map.json") == "old map");
    CHECK_FALSE(fs::exists(dir / "stage.summary.json"));
    CHECK(tx.staged() == 3);
    tx.commit();
  }
  CHECK(io::readBytes(dir / "map.json") == "new map");
  CHECK(io::readBytes(dir / "sub" / "labels.bin") == "labels");
  CHECK(io::readBytes(dir / "stage.summary.json") == "summary");
  CHECK(temporaries(dir) == 0);
}

TEST_CASE("a failed run leaves the previous outputs byte-identical", "[io][output]") {
  const auto dir = test::tempDir("tx-fail");
  io::writeBytesAtomic(dir / "a.json", "previous a");
  io::writeBytesAtomic(dir / "b.json", "previous b");
  try {
    io::OutputTransaction tx(dir);
    io::writeBytesAtomic(dir / "a.json", "half of a new set");
    throw InputError("the run failed after writing a");
  } catch (const InputError&) {
  }
  CHECK(io::readBytes(dir / "a.json") == "previous a");
  CHECK(io::readBytes(dir / "b.json") == "previous b");
  CHECK(temporaries(dir) == 0);

  // A folder where a later output should go: nothing of the set is replaced.
  {
    io::OutputTransaction tx(dir);
    io::writeBytesAtomic(dir / "a.json", "new a");
    fs::remove(dir / "b.json");
    fs::create_directories(dir / "b.json");
    io::writeBytesAtomic(dir / "b.json", "new b");
    CHECK_THROWS_WITH(tx.commit(), Catch::Contains((dir / "b.json").string()));
  }
  CHECK(io::readBytes(dir / "a.json") == "previous a");
  CHECK(temporaries(dir) == 0);
}

TEST_CASE("the output folder is locked and checked before any work", "[io][output]") {
  const auto dir = test::tempDir("tx-lock");
  {
    io::OutputTransaction tx(dir);
    // another process cannot take the lock while this run holds it
    const std::string lock = (dir / ".mapfuse.lock").string();
    CHECK(test::runCommand("flock -n " + lock + " true") != 0);
    CHECK_THROWS_AS(io::OutputTransaction(dir / "other"), std::logic_error);  // one per process
  }
  // held by another process: refused with an I/O error (exit 4) naming the folder
  const std::string lock = (dir / ".mapfuse.lock").string();
  REQUIRE(test::runCommand("flock " + lock + " sleep 3 & sleep 0.5") == 0);
  try {
    io::OutputTransaction tx(dir);
    FAIL("a locked folder was accepted");
  } catch (const IoError& e) {
    CHECK_THAT(e.what(), Catch::Contains(dir.string()));
    CHECK_THAT(e.what(), Catch::Contains("another mapfuse run"));
    CHECK(e.exitCode() == ExitCode::kIo);
  }
  // a regular file where the folder should be: refused at once
  test::writeText(dir / "file", "x");
  CHECK_THROWS_AS(io::OutputTransaction(dir / "file" / "out"), IoError);
}

TEST_CASE("temporary files of dead runs are removed, a live run's are kept", "[io][output]") {
  const auto dir = test::tempDir("tx-stale");
  const auto dead = dir / "sub" / ("map.json.tmp-" + std::to_string(deadPid()));
  const auto live = dir / ("map.json.tmp-" + std::to_string(::getppid()));
  // a writer that picks its format by the extension (OpenCV's forests)
  const auto dead_ext = dir / ("rtrees_3.yml.tmp-" + std::to_string(deadPid()) + ".yml");
  const auto not_temp = dir / ("notes.tmp-" + std::to_string(deadPid()) + ".v2");  // not ours
  test::writeText(dead, "left by a killed run");
  test::writeText(live, "being written by a running process");
  test::writeText(dead_ext, "left by a killed train run");
  test::writeText(not_temp, "a user's file");
  { io::OutputTransaction tx(dir); }
  CHECK_FALSE(fs::exists(dead));
  CHECK_FALSE(fs::exists(dead_ext));
  CHECK(fs::exists(live));
  CHECK(fs::exists(not_temp));
}

TEST_CASE("a run that fails leaves no folder or lock behind that it created", "[io][output]") {
  const auto base = test::tempDir("tx-refused");
  const fs::path fresh = base / "new" / "deeper/";  // two levels that did not exist
  try {
    io::OutputTransaction tx(fresh);
    CHECK(fs::exists(fresh / ".mapfuse.lock"));
    throw InputError("refused: the map has no roads");
  } catch (const InputError&) {
  }
  CHECK_FALSE(fs::exists(base / "new"));  // absent stays absent
  CHECK(fs::exists(base));                // what was there stays

  // An existing folder with a previous run's outputs and lock: all kept.
  io::writeBytesAtomic(base / "kept" / "a.json", "previous a");
  {
    io::OutputTransaction tx(base / "kept");
    tx.commit();
  }
  REQUIRE(fs::exists(base / "kept" / ".mapfuse.lock"));
  try {
    io::OutputTransaction tx(base / "kept");
    throw InputError("refused");
  } catch (const InputError&) {
  }
  CHECK(fs::exists(base / "kept" / ".mapfuse.lock"));
  CHECK(io::readBytes(base / "kept" / "a.json") == "previous a");

  // An existing empty folder: the lock this run created goes, the folder stays.
  fs::create_directories(base / "empty");
  try {
    io::OutputTransaction tx(base / "empty");
    throw InputError("refused");
  } catch (const InputError&) {
  }
  CHECK(fs::exists(base / "empty"));
  CHECK(fs::is_empty(base / "empty"));

  // A committed run keeps its folder and lock.
  {
    io::OutputTransaction tx(base / "done");
    io::writeBytesAtomic(base / "done" / "x", "x");
    tx.commit();
  }
  CHECK(fs::exists(base / "done" / "x"));
}
