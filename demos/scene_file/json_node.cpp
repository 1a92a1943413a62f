#include "scene_file/json_node.h"

#include <cctype>
#include <cmath>

#include "particles/check.h"

namespace scenes {


std::string describeValue(const Json& value, std::size_t maxChars) {
  // Depth-first over an explicit stack of open containers and the next
  // element of each; scalars are dumped (they hold no further values).
  struct Open {
    const Json* container;
    std::size_t next;
  };
  std::string text;
  std::vector<Open> stack;
  const auto emit = [&](const Json& v) {
    if (v.is_object()) {
      text += '{';
      stack.push_back({&v, 0});
    } else if (v.is_array()) {
      text += '[';
      stack.push_back({&v, 0});
    } else {
      text += v.dump(-1, ' ', false, Json::error_handler_t::replace);
    }
  };
  emit(value);
  while (!stack.empty() && text.size() <= maxChars) {
    Open& top = stack.back();
    const Json& c = *top.container;
    if (top.next == c.size()) {
      text += c.is_object() ? '}' : ']';
      stack.pop_back();
      continue;
    }
    if (top.next > 0) text += ',';
    const std::size_t k = top.next++;
    if (c.is_object()) {
      const auto& member = static_cast<const Json::object_t::Container&>(c.get_ref<const Json::object_t&>())[k];
      text += Json(member.first).dump(-1, ' ', false, Json::error_handler_t::replace) + ':';
      emit(member.second);
    } else {
      emit(c[k]);
    }
  }
  if (text.size() > maxChars) text = text.substr(0, maxChars - 3) + "...";
  return text;
}

std::string memberPath(const std::string& key) {
  bool plain = !key.empty();
  for (char c : key) plain = plain && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-');
  return plain ? "." + key : "[" + Json(key).dump(-1, ' ', false, Json::error_handler_t::replace) + "]";
}

namespace {
// The offending value, shortened to stay on one line.
std::string describe(const Json* value) { return value ? describeValue(*value) : "nothing (the field is missing)"; }
}  // namespace

void JsonNode::expected(const std::string& what) const {
  throw SceneFileError(path_ + ": expected " + what + ", got " + describe(value_));
}

void JsonNode::reject(const std::string& reason) const { throw SceneFileError(path_ + ": " + reason); }

const Json& JsonNode::require(bool ok, const char* what) const {
  if (!value_ || !ok) expected(what);
  return *value_;
}

JsonNode JsonNode::operator[](const char* key) const {
  const Json& object = require(value_ && value_->is_object(), "an object");
  const auto it = object.find(key);
  return JsonNode(it == object.end() ? nullptr : &*it, path_ + memberPath(key));
}

JsonNode JsonNode::operator[](std::size_t index) const {
  const Json& array = require(value_ && value_->is_array(), "an array");
  return JsonNode(index < array.size() ? &array[index] : nullptr, path_ + "[" + std::to_string(index) + "]");
}

std::size_t JsonNode::arraySize() const {
  if (!value_) return 0;
  return require(value_->is_array(), "an array").size();
}

void JsonNode::allowOnly(std::initializer_list<const char*> keys) const {
  const Json& object = require(value_ && value_->is_object(), "an object");
  for (const auto& item : object.items()) {
    bool known = false;
    std::string list;
    for (const char* key : keys) {
      known = known || item.key() == key;
      list += list.empty() ? "" : ", ";
      list += key;
    }
    if (!known) (*this)[item.key().c_str()].reject("unknown field (valid here: " + list + ")");
  }
}

double JsonNode::numberWhere(const std::string& what, bool (*ok)(double, double, double), double lo,
                             double hi) const {
  const Json& v = require(value_ && value_->is_number(), what.c_str());
  const double x = v.get<double>();
  if (!std::isfinite(x) || !ok(x, lo, hi)) expected(what);
  return x;
}

double JsonNode::number() const {
  return numberWhere("a finite number", [](double, double, double) { return true; });
}

double JsonNode::positive() const {
  return numberWhere("a number > 0", [](double x, double, double) { return x > 0.0; });
}

double JsonNode::nonNegative() const {
  return numberWhere("a number >= 0", [](double x, double, double) { return x >= 0.0; });
}

double JsonNode::inRange(double lo, double hi) const {
  return numberWhere("a number in [" + particles::formatValue(lo) + ", " + particles::formatValue(hi) + "]",
                     [](double x, double a, double b) { return x >= a && x <= b; }, lo, hi);
}

int JsonNode::integerWhere(const std::string& what, int lo, int hi) const {
  const Json& v = require(value_ && value_->is_number_integer(), what.c_str());
  // Non-negative integers are stored unsigned and may exceed int64.
  const bool inRange = v.is_number_unsigned()
                           ? hi >= 0 && v.get<std::uint64_t>() <= std::uint64_t(hi) &&
                                 (lo <= 0 || v.get<std::uint64_t>() >= std::uint64_t(lo))
                           : v.get<std::int64_t>() >= lo && v.get<std::int64_t>() <= hi;
  if (!inRange) expected(what);
  return static_cast<int>(v.get<std::int64_t>());
}

int JsonNode::integer(int lo, int hi) const {
  return integerWhere("an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]", lo, hi);
}

int JsonNode::particle(int particleCount) const {
  return integerWhere("a particle index in [0, " + std::to_string(particleCount) + ")", 0, particleCount - 1);
}

std::vector<int> JsonNode::particles(std::size_t count, int particleCount) const {
  const std::string what = "an array of " + std::to_string(count) + " particle indices";
  require(value_ && value_->is_array() && value_->size() == count, what.c_str());
  std::vector<int> indices;
  for (std::size_t k = 0; k < count; ++k) indices.push_back((*this)[k].particle(particleCount));
  return indices;
}

std::vector<int> JsonNode::ring(int particleCount, std::size_t maxCount) const {
  const std::string what = "an array of 3 to " + std::to_string(maxCount) + " particle indices (a closed ring)";
  require(value_ && value_->is_array() && value_->size() >= 3 && value_->size() <= maxCount, what.c_str());
  std::vector<int> indices;
  for (std::size_t k = 0; k < value_->size(); ++k) indices.push_back((*this)[k].particle(particleCount));
  return indices;
}

bool JsonNode::boolean() const { return require(value_ && value_->is_boolean(), "true or false").get<bool>(); }

std::string JsonNode::text() const {
  return require(value_ && value_->is_string(), "a string").get<std::string>();
}

Eigen::Vector2d JsonNode::vec2() const {
  require(value_ && value_->is_array() && value_->size() == 2, "a point [x, y]");
  return Eigen::Vector2d((*this)[std::size_t(0)].number(), (*this)[std::size_t(1)].number());
}

}  // namespace scenes
