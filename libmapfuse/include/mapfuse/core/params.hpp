#pragma once
/// @file Stage parameters. Every stage's Params struct lists its fields once, in a
/// `template <class V> void visit(V& v)` member:
///
///   v("max_iterations", max_iterations, "", "Gauss-Newton iterations per level");
///   v("voxel_size", voxel_size, "m", "voxel edge length");
///
/// and these helpers turn that one list into JSON (configs/<stage>.json, the resolved config
/// beside the outputs), strict JSON parsing (unknown keys are errors) and CLI options.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/json_view.hpp"

namespace mapfuse {

namespace detail {
struct ToJsonVisitor {
  nlohmann::json& j;
  template <class T>
  void operator()(const char* key, T& value, const char* /*unit*/, const char* /*help*/) {
    j[key] = value;
  }
};

struct FromJsonVisitor {
  const io::JsonView& view;
  template <class T>
  void operator()(const char* key, T& value, const char* /*unit*/, const char* /*help*/) {
    auto field = view.find(key);
    if (!field) return;
    if constexpr (std::is_same_v<T, bool>)
      value = field->boolean();
    else if constexpr (std::is_integral_v<T>) {
      const int64_t v = field->integer();
      if (std::is_unsigned_v<T> && v < 0) field->fail("must not be negative");
      value = static_cast<T>(v);
    } else if constexpr (std::is_floating_point_v<T>)
      value = static_cast<T>(field->number());
    else
      value = field->string();
  }
};

struct KeyCheckVisitor {
  const std::string& key;
  bool found = false;
  template <class T>
  void operator()(const char* k, T&, const char*, const char*) {
    found = found || key == k;
  }
};
}  // namespace detail

/// @brief All fields of a Params struct as a JSON object.
template <class Params>
nlohmann::json paramsToJson(const Params& params) {
  nlohmann::json j = nlohmann::json::object();
  Params copy = params;
  detail::ToJsonVisitor v{j};
  copy.visit(v);
  return j;
}

/// @brief Overrides fields of `params` from a JSON object; unknown keys throw ConfigError
/// naming the file and the key.
template <class Params>
void paramsFromJson(Params& params, const nlohmann::json& j, const std::string& file) {
  const io::JsonView view(j, file, "", /*is_config=*/true);
  if (!j.is_object()) view.fail("a configuration must be a JSON object");
  for (auto it = j.begin(); it != j.end(); ++it) {
    detail::KeyCheckVisitor check{it.key()};
    params.visit(check);
    if (!check.found) view.at(it.key()).fail("unknown configuration key");
  }
  detail::FromJsonVisitor v{view};
  params.visit(v);
}

/// @brief Throws ConfigError "<Stage>::<field> = <value>. Violated constraint: <rule>"
/// unless `ok` holds; used by each Params::validate().
template <class T>
void requireParam(bool ok, const char* stage, const char* field, const T& value, const char* rule) {
  if (ok) return;
  throw ConfigError(std::string(stage) + "::" + field + " = " + nlohmann::json(value).dump() +
                    ". Violated constraint: " + rule);
}

}  // namespace mapfuse
