#pragma once
/// @file Parameters in and out of files: the resolved config (JSON), strict config-file reading
/// (unknown keys, nulls, wrong types, out-of-range values and integers that would not fit are
/// ConfigErrors naming the file and the key) and validation. All of it follows from each
/// Params struct's one list of declarations (mapfuse/core/param.hpp):
///
///   struct AlignParams {
///     static constexpr const char* kName = "AlignParams";  // names the owner in messages
///     fusion::AlignSettings align;                          // composed of area Settings
///     template <class V> void visit(V& v) { align.visit(v); }
///   };
#include <cmath>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/core/param_check.hpp"
#include "mapfuse/io/json_view.hpp"

namespace mapfuse {

namespace detail {
using param::kIsNumber;
using param::showValue;

struct ToJsonVisitor {
  nlohmann::json& j;
  template <class T, class... Rule>
  void operator()(const char* key, T& value, const char*, const char*, const Rule&...) {
    j[key] = value;
  }
  template <class E>
  void operator()(const char* key, E& value, const char*, const char*,
                  const param::Names<E>& names) {
    j[key] = names.nameOf(value);
  }
  template <class T>
  void relation(const char*, const T&, bool, const char*) {}
};

struct FromJsonVisitor {
  const io::JsonView& view;

  /// The member `key`, or nothing when absent; null is an error, not a default.
  std::optional<io::JsonView> member(const char* key) const {
    const auto& raw = view.raw();
    const auto it = raw.find(key);
    if (it == raw.end()) return std::nullopt;
    io::JsonView field(*it, view.file(), key, /*is_config=*/true);
    if (it->is_null()) field.fail("null is not a value (give one, or leave the key out)");
    return field;
  }

  /// Reads a number (integers range-checked before they are narrowed), a bool or a text.
  template <class T>
  static void read(const io::JsonView& field, T& value) {
    if constexpr (std::is_same_v<T, bool>) {
      value = field.boolean();
    } else if constexpr (std::is_integral_v<T>) {
      const int64_t v = field.integer();
      if ((std::is_unsigned_v<T> && v < 0) ||
          (v > 0 && static_cast<uint64_t>(v) > uint64_t(std::numeric_limits<T>::max())) ||
          (std::is_signed_v<T> && v < int64_t(std::numeric_limits<T>::min())))
        field.fail(std::to_string(v) + " does not fit a " + std::to_string(8 * sizeof(T)) +
                   "-bit " + (std::is_signed_v<T> ? "" : "unsigned ") + "integer");
      value = static_cast<T>(v);
    } else if constexpr (std::is_floating_point_v<T>) {
      value = static_cast<T>(field.number());  // finite
    } else {
      value = field.string();
    }
  }

  template <class T>
  void operator()(const char* key, T& value, const char*, const char*, const param::Range& range) {
    static_assert(kIsNumber<T>, "a Range rules numbers");
    const auto field = member(key);
    if (!field) return;
    read(*field, value);
    if (!range.contains(static_cast<double>(value)))
      field->fail(showValue(value) + " violates " + range.describe(key));
  }
  /// bool, free text (and, until every stage declares its rules, numbers without one).
  template <class T>
  void operator()(const char* key, T& value, const char*, const char*) {
    if (const auto field = member(key)) read(*field, value);
  }
  void operator()(const char* key, std::string& value, const char*, const char*,
                  const param::OneOf& names) {
    const auto field = member(key);
    if (!field) return;
    value = field->string();
    if (!names.contains(value)) field->fail(showValue(value) + " is not " + names.describe(key));
  }
  void operator()(const char* key, std::string& value, const char*, const char*,
                  const param::TextRule& rule) {
    const auto field = member(key);
    if (!field) return;
    value = field->string();
    if (!rule.ok(value)) field->fail(showValue(value) + " is not " + rule.text);
  }
  /// A list of numbers: a JSON array, each value finite, size and range per the rule.
  void operator()(const char* key, std::vector<double>& values, const char*, const char*,
                  const param::ListRule& rule) {
    const auto field = member(key);
    if (!field) return;
    if (!field->raw().is_array()) field->fail("must be an array of numbers");
    std::vector<double> read_values;
    for (std::size_t i = 0; i < field->raw().size(); ++i)
      read_values.push_back(field->at(i).number());
    if (!rule.contains(read_values))
      field->fail(param::showList(read_values) + " violates " + rule.describe(key));
    values = std::move(read_values);
  }
  template <class E>
  void operator()(const char* key, E& value, const char*, const char*,
                  const param::Names<E>& names) {
    const auto field = member(key);
    if (!field) return;
    if (!names.find(field->string(), &value))
      field->fail(showValue(field->string()) + " is not " + names.oneOf().describe(key));
  }
  template <class T>
  void relation(const char*, const T&, bool, const char*) {}
};

}  // namespace detail

/// Where and how a parameter is declared (for the "declared once" test and the docs).
struct ParamDeclaration {
  std::string key, unit, help;
  std::string kind;    ///< "integer", "number", "bool", "text", "choice" or "list"
  std::string rule;    ///< "" for bool and free text
  param::Range range;  ///< numbers: the declared range; lists: the range of each value
  std::string file;    ///< source file of the `v(...)` line
  int line = 0;
};

namespace detail {
struct DeclarationVisitor {
  std::vector<ParamDeclaration>& out;
  template <class T>
  static const char* kindOf() {
    if constexpr (std::is_same_v<T, bool>) return "bool";
    if constexpr (std::is_integral_v<T>) return "integer";
    if constexpr (std::is_floating_point_v<T>) return "number";
    return "text";
  }
  template <class T>
  void operator()(const char* key, T&, const char* unit, const char* help,
                  const param::Range& range, const char* file = __builtin_FILE(),
                  int line = __builtin_LINE()) {
    out.push_back({key, unit, help, kindOf<T>(), range.describe(key), range, file, line});
  }
  template <class T>
  void operator()(const char* key, T&, const char* unit, const char* help,
                  const char* file = __builtin_FILE(), int line = __builtin_LINE()) {
    out.push_back({key, unit, help, kindOf<T>(), "", {}, file, line});
  }
  void operator()(const char* key, std::string&, const char* unit, const char* help,
                  const param::OneOf& names, const char* file = __builtin_FILE(),
                  int line = __builtin_LINE()) {
    out.push_back({key, unit, help, "choice", names.describe(key), {}, file, line});
  }
  void operator()(const char* key, std::string&, const char* unit, const char* help,
                  const param::TextRule& rule, const char* file = __builtin_FILE(),
                  int line = __builtin_LINE()) {
    out.push_back({key, unit, help, "text", rule.text, {}, file, line});
  }
  void operator()(const char* key, std::vector<double>&, const char* unit, const char* help,
                  const param::ListRule& rule, const char* file = __builtin_FILE(),
                  int line = __builtin_LINE()) {
    out.push_back({key, unit, help, "list", rule.describe(key), rule.each, file, line});
  }
  template <class E>
  void operator()(const char* key, E&, const char* unit, const char* help,
                  const param::Names<E>& names, const char* file = __builtin_FILE(),
                  int line = __builtin_LINE()) {
    out.push_back({key, unit, help, "choice", names.oneOf().describe(key), {}, file, line});
  }
  template <class T>
  void relation(const char*, const T&, bool, const char*) {}
};
}  // namespace detail

/// @brief Every parameter of a Params struct, in declaration order, with where it is declared.
template <class Params>
std::vector<ParamDeclaration> paramDeclarations() {
  std::vector<ParamDeclaration> out;
  Params p;
  detail::DeclarationVisitor v{out};
  p.visit(v);
  return out;
}

/// @brief All fields of a Params struct as a JSON object (the resolved config).
template <class Params>
nlohmann::json paramsToJson(const Params& params) {
  nlohmann::json j = nlohmann::json::object();
  Params copy = params;
  detail::ToJsonVisitor v{j};
  copy.visit(v);
  return j;
}

/// @brief Overrides fields of `params` from a JSON object. Unknown keys, nulls, wrong types,
/// integers that do not fit and values outside a parameter's rule throw ConfigError naming
/// `file` and the key.
template <class Params>
void paramsFromJson(Params& params, const nlohmann::json& j, const std::string& file) {
  const io::JsonView view(j, file, "", /*is_config=*/true);
  if (!j.is_object()) view.fail("a configuration must be a JSON object");
  std::set<std::string> keys;
  for (const auto& d : paramDeclarations<Params>()) keys.insert(d.key);
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!keys.count(it.key())) view.at(it.key()).fail("unknown configuration key");
  detail::FromJsonVisitor v{view};
  params.visit(v);
}

/// @brief Checks every declared rule (numbers finite and in range, names known, relations).
/// @throws ConfigError "<owner>::<key> = <value>. Violated constraint: <rule>"; `owner` is the
/// stage's Params name (Params::kName) unless given.
template <class Params>
void validateParams(const Params& params, const char* owner = Params::kName) {
  param::validate(params, owner);
}

/// @brief Reads a config file (JSON) into `params`: like paramsFromJson, and an unreadable,
/// empty or malformed file is a ConfigError (exit 2) too, naming the file.
template <class Params>
void paramsFromFile(Params& params, const std::string& file);

/// @brief The parsed JSON of a config file; every problem is a ConfigError naming the file
/// (IoError when it cannot be read).
nlohmann::json readConfigFile(const std::string& file);

template <class Params>
void paramsFromFile(Params& params, const std::string& file) {
  paramsFromJson(params, readConfigFile(file), file);
}

}  // namespace mapfuse
