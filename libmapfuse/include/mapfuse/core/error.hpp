#pragma once
/// @file The mapfuse exception hierarchy and the documented exit codes (docs/cli.md).
#include <stdexcept>
#include <string>

namespace mapfuse {

/// Process exit codes shared by every tool.
enum class ExitCode : int {
  kOk = 0,        ///< success
  kInternal = 1,  ///< a bug or an unexpected failure
  kUsage = 2,     ///< bad command line or configuration
  kBadInput = 3,  ///< an input file is malformed or inconsistent
  kIo = 4,        ///< a file could not be read or written
};

/// Base of every error mapfuse throws on purpose.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
  virtual ExitCode exitCode() const { return ExitCode::kInternal; }
};

/// A file or folder could not be opened, read, written or renamed.
class IoError : public Error {
 public:
  IoError(const std::string& path, const std::string& problem)
      : Error(path + ": " + problem), path_(path) {}
  ExitCode exitCode() const override { return ExitCode::kIo; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// A file was read but its content is malformed: names the file, the field and the problem.
class ParseError : public Error {
 public:
  ParseError(const std::string& file, const std::string& field, const std::string& problem)
      : Error(file + ": " + (field.empty() ? std::string() : "field '" + field + "': ") + problem),
        file_(file),
        field_(field),
        problem_(problem) {}
  ExitCode exitCode() const override { return ExitCode::kBadInput; }
  const std::string& file() const { return file_; }
  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string file_, field_, problem_;
};

/// Input data is well formed but unusable (e.g. inconsistent frame counts, no overlap).
class InputError : public Error {
 public:
  explicit InputError(const std::string& message) : Error(message) {}
  ExitCode exitCode() const override { return ExitCode::kBadInput; }
};

/// A parameter or configuration file is invalid: names the field, the value and the rule.
class ConfigError : public Error {
 public:
  explicit ConfigError(const std::string& message) : Error(message) {}
  ExitCode exitCode() const override { return ExitCode::kUsage; }
};

}  // namespace mapfuse
