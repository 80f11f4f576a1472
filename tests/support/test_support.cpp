#include "support/test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "mapfuse/core/paths.hpp"
#include "mapfuse/io/document.hpp"

namespace mapfuse::test {

std::filesystem::path requireShared(const std::string& relative) {
  const std::filesystem::path path = sharedRoot() / relative;
  if (!std::filesystem::exists(path)) {
    std::cout << "SKIP: shared data absent: " << path
              << " (set MAPFUSE_SHARED to the folder holding data/ and models/)" << std::endl;
    std::exit(kSkipExitCode);
  }
  return path;
}

std::filesystem::path tempDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("mapfuse-test-" + std::to_string(::getpid()) + "-" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::filesystem::path appPath(const std::string& tool) {
  const char* env = std::getenv("MAPFUSE_BIN_DIR");
  std::filesystem::path dir = env ? env : MAPFUSE_BIN_DIR;
  return dir / tool;
}

int runCommand(const std::string& command) {
  const int status = std::system(command.c_str());
  if (status == -1) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

int simulateTruthOn(const std::filesystem::path& dir, const std::string& map,
                    const std::string& extra, const std::string& name) {
  return runCommand(appPath("simulate").string() + " --map " + (dir / map).string() +
                    " --traversals 1 --route-length 60 --level truth " + extra + " -o " +
                    (dir / name).string() + " > /dev/null 2> " + (dir / (name + ".err")).string());
}

void writeText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

nlohmann::json readSummary(const std::filesystem::path& dir, const std::string& stage) {
  return io::readDocument(dir / (stage + ".summary.json"));
}

}  // namespace mapfuse::test
