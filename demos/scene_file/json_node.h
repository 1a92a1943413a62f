#pragma once
// Reading a JSON scene file value by value, each read knowing the JSON path of
// its value, so that anything malformed is rejected with one line naming the
// path, what was expected and what was found.
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace scenes {

// Objects keep their members in file order, so written files read naturally.
using Json = nlohmann::ordered_json;

// A rejected scene file: what() is the whole one-line message.
class SceneFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The path step of an object member: ".key" for a plain name, else ["key"]
// escaped as JSON, so that a path stays on one line whatever a key holds.
std::string memberPath(const std::string& key);

// A value as it appears in a file, cut to at most maxChars characters ("..."
// at the end when cut). Iterative, so a deeply nested value cannot exhaust
// the stack, and it reads only as much of the value as it shows.
std::string describeValue(const Json& value, std::size_t maxChars = 40);

class JsonNode {
 public:
  JsonNode(const Json* value, std::string path) : value_(value), path_(std::move(path)) {}

  const std::string& path() const { return path_; }
  bool present() const { return value_ != nullptr; }

  // Members and elements. A missing member is not an error until it is read.
  JsonNode operator[](const char* key) const;
  JsonNode operator[](std::size_t index) const;
  std::size_t arraySize() const;  // requires an array; an absent one counts as empty
  // Rejects members other than these (catches misspelt optional fields).
  void allowOnly(std::initializer_list<const char*> keys) const;

  double number() const;        // finite
  double positive() const;      // finite, > 0
  double nonNegative() const;   // finite, >= 0
  double inRange(double lo, double hi) const;
  int integer(int lo, int hi) const;
  int particle(int particleCount) const;  // an index in [0, particleCount)
  std::vector<int> particles(std::size_t count, int particleCount) const;  // array of indices
  // A closed ring: an array of at least 3 and at most maxCount indices.
  std::vector<int> ring(int particleCount, std::size_t maxCount) const;
  bool boolean() const;
  std::string text() const;
  Eigen::Vector2d vec2() const;  // [x, y], finite

  // boolean() with a default for an absent member.
  bool boolean(bool fallback) const { return present() ? boolean() : fallback; }

  // Throws SceneFileError "path: expected <what>, got <value>".
  [[noreturn]] void expected(const std::string& what) const;
  // Throws SceneFileError "path: <reason>" (an engine object refused the values).
  [[noreturn]] void reject(const std::string& reason) const;

 private:
  const Json& require(bool ok, const char* what) const;
  int integerWhere(const std::string& what, int lo, int hi) const;  // an integer in [lo, hi]
  // A finite number for which ok(x, lo, hi) holds, or an error naming what.
  double numberWhere(const std::string& what, bool (*ok)(double, double, double), double lo = 0.0,
                     double hi = 0.0) const;
  const Json* value_;
  std::string path_;
};

}  // namespace scenes
