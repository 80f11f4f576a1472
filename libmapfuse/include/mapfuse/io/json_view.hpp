#pragma once
/// @file Strict, path-tracking access to parsed JSON (or CBOR) documents. Every accessor throws
/// ParseError (or ConfigError for configuration files) naming the file, the field path
/// (e.g. "keyframes[3].t") and the problem: missing, wrong type, not finite, unknown key.
#include <Eigen/Core>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "mapfuse/io/bounds.hpp"

namespace mapfuse::io {

using Json = nlohmann::json;

class JsonView {
 public:
  /// @param is_config throw ConfigError (exit 2) instead of ParseError (exit 3).
  JsonView(const Json& node, std::string file, std::string path = "", bool is_config = false);

  const Json& raw() const { return *node_; }
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }

  bool has(const std::string& key) const;
  /// @brief Required member of an object.
  JsonView at(const std::string& key) const;
  /// @brief Optional member; nullopt when absent (null counts as absent).
  std::optional<JsonView> find(const std::string& key) const;
  /// @brief Element i of an array.
  JsonView at(std::size_t i) const;
  /// @brief Number of elements; the node must be an array.
  std::size_t size() const;

  double number() const;    ///< finite number
  int64_t integer() const;  ///< integral number that fits in int64
  /// @brief A finite number within [lo, hi]; fails naming the range otherwise.
  double number(double lo, double hi) const;
  /// @brief An integer within [lo, hi] (checked before any narrowing by the caller).
  int64_t integer(int64_t lo, int64_t hi) const;
  /// @brief An integer that fits in `int` and is at least `lo`.
  int integerInt(int lo = std::numeric_limits<int>::min()) const;
  std::string string() const;
  bool boolean() const;
  Eigen::Vector3d vec3() const;  ///< array of exactly 3 finite numbers
  /// @brief vec3() with every component within [-limit, limit].
  Eigen::Vector3d coordinate(double limit = bounds::kMaxCoordinate) const;
  Eigen::VectorXd vector(std::size_t expected_size) const;  ///< 0 = any size

  /// @brief The node must be an object whose keys are all in `allowed`.
  void onlyKeys(std::initializer_list<const char*> allowed) const;
  /// @brief Checks `format` and `version` members against the expected values.
  void checkFormat(const std::string& format, int max_version) const;

  /// @brief Throws the error this view would throw, for problems its caller finds.
  [[noreturn]] void fail(const std::string& problem) const;

 private:
  void requireObject() const;
  void requireArray() const;
  const Json* node_;
  std::string file_;
  std::string path_;
  bool is_config_;
};

}  // namespace mapfuse::io
