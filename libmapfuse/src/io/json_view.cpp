#include "mapfuse/io/json_view.hpp"

#include <cmath>
#include <limits>

#include "mapfuse/core/error.hpp"

namespace mapfuse::io {

JsonView::JsonView(const Json& node, std::string file, std::string path, bool is_config)
    : node_(&node), file_(std::move(file)), path_(std::move(path)), is_config_(is_config) {}

void JsonView::fail(const std::string& problem) const {
  if (is_config_)
    throw ConfigError(file_ + ": " + (path_.empty() ? "" : "field '" + path_ + "': ") + problem);
  throw ParseError(file_, path_, problem);
}

static std::string typeName(const Json& j) {
  return j.type_name();
}

void JsonView::requireObject() const {
  if (!node_->is_object()) fail("expected an object, found " + typeName(*node_));
}
void JsonView::requireArray() const {
  if (!node_->is_array()) fail("expected an array, found " + typeName(*node_));
}

bool JsonView::has(const std::string& key) const {
  requireObject();
  auto it = node_->find(key);
  return it != node_->end() && !it->is_null();
}

JsonView JsonView::at(const std::string& key) const {
  requireObject();
  auto it = node_->find(key);
  const std::string child = path_.empty() ? key : path_ + "." + key;
  if (it == node_->end() || it->is_null())
    JsonView(*node_, file_, child, is_config_).fail("missing required field");
  return JsonView(*it, file_, child, is_config_);
}

std::optional<JsonView> JsonView::find(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return at(key);
}

JsonView JsonView::at(std::size_t i) const {
  requireArray();
  if (i >= node_->size()) fail("index " + std::to_string(i) + " out of range");
  return JsonView((*node_)[i], file_, path_ + "[" + std::to_string(i) + "]", is_config_);
}

std::size_t JsonView::size() const {
  requireArray();
  return node_->size();
}

double JsonView::number() const {
  if (!node_->is_number()) fail("expected a number, found " + typeName(*node_));
  const double v = node_->get<double>();
  if (!std::isfinite(v)) fail("number is not finite");
  return v;
}

int64_t JsonView::integer() const {
  if (node_->is_number_unsigned()) {
    if (node_->get<uint64_t>() > uint64_t(std::numeric_limits<int64_t>::max()))
      fail("integer " + std::to_string(node_->get<uint64_t>()) + " is too large");
    return int64_t(node_->get<uint64_t>());
  }
  if (node_->is_number_integer()) return node_->get<int64_t>();
  if (node_->is_number_float()) {
    const double v = node_->get<double>();
    if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 9e15) return int64_t(v);
  }
  fail("expected an integer, found " + typeName(*node_));
}

double JsonView::number(double lo, double hi) const {
  const double v = number();
  if (!bounds::within(v, lo, hi))
    fail("value " + nlohmann::json(v).dump() + " is outside " + bounds::rangeText(lo, hi));
  return v;
}

int64_t JsonView::integer(int64_t lo, int64_t hi) const {
  const int64_t v = integer();
  if (v < lo || v > hi)
    fail("value " + std::to_string(v) + " is outside [" + std::to_string(lo) + ", " +
         std::to_string(hi) + "]");
  return v;
}

int JsonView::integerInt(int lo) const {
  return int(integer(lo, std::numeric_limits<int>::max()));
}

std::string JsonView::string() const {
  if (!node_->is_string()) fail("expected a string, found " + typeName(*node_));
  return node_->get<std::string>();
}

bool JsonView::boolean() const {
  if (!node_->is_boolean()) fail("expected true or false, found " + typeName(*node_));
  return node_->get<bool>();
}

Eigen::Vector3d JsonView::vec3() const {
  const Eigen::VectorXd v = vector(3);
  return v.head<3>();
}

Eigen::Vector3d JsonView::coordinate(double limit) const {
  const Eigen::Vector3d v = vec3();
  for (int k = 0; k < 3; ++k)
    if (std::abs(v[k]) > limit)
      at(std::size_t(k))
          .fail("coordinate " + nlohmann::json(v[k]).dump() + " m is outside " +
                bounds::rangeText(-limit, limit));
  return v;
}

Eigen::VectorXd JsonView::vector(std::size_t expected_size) const {
  requireArray();
  if (expected_size != 0 && node_->size() != expected_size)
    fail("expected " + std::to_string(expected_size) + " numbers, found " +
         std::to_string(node_->size()));
  Eigen::VectorXd v(node_->size());
  for (std::size_t i = 0; i < node_->size(); ++i) v[i] = at(i).number();
  return v;
}

void JsonView::onlyKeys(std::initializer_list<const char*> allowed) const {
  requireObject();
  for (auto it = node_->begin(); it != node_->end(); ++it) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || it.key() == a;
    if (!ok) {
      std::string list;
      for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
      JsonView(*it, file_, path_.empty() ? it.key() : path_ + "." + it.key(), is_config_)
          .fail("unknown key (allowed: " + list + ")");
    }
  }
}

void JsonView::checkFormat(const std::string& format, int max_version) const {
  const std::string f = at("format").string();
  if (f != format) at("format").fail("expected \"" + format + "\", found \"" + f + "\"");
  const int64_t v = at("version").integer();
  if (v < 1 || v > max_version)
    at("version").fail("unsupported version " + std::to_string(v) + " (this build reads 1.." +
                       std::to_string(max_version) + ")");
}

}  // namespace mapfuse::io
