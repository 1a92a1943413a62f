#pragma once
// Cell results as JSON (lab/cells.h). Each result type lists its fields once,
// in a `fields(io, value)` function beside it; encode and decode walk that
// list. Every value is kept exactly: finite doubles as JSON numbers (written
// as the shortest text that reads back to the same double), NaN and ±inf —
// which JSON lacks — as the strings "nan", "inf" and "-inf".
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace lab {

using Json = nlohmann::json;

// A recorded value that does not read back as its type (a merge of shards
// made by another version, or edited): what() is the place in the result, as
// a JSON path from the result ($), and what was found there, in the
// program's words, e.g.
//   $.samples[3]: expected an array of 2 values, got [1,2,3]
//   $: no field 'last'
// Every decode() checks the JSON type and shape before it reads (an array of
// exactly the pair's two values, an object with exactly the struct's fields,
// an integer where an integer is, within its type's range).
class CellShapeError : public std::invalid_argument {
 public:
  CellShapeError(std::string path, const std::string& problem)
      : std::invalid_argument("$" + path + ": " + problem), path_(std::move(path)), problem_(problem) {}
  const std::string& path() const { return path_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string path_, problem_;
};

namespace detail {
// Throws CellShapeError "$: expected <what>, got <j, cut short>".
[[noreturn]] void wrongShape(const Json& j, const std::string& what);
// Runs read(); a CellShapeError from inside gets `step` (".name", "[k]") in front of its path.
template <class Read>
void within(const std::string& step, Read&& read) {
  try {
    read();
  } catch (const CellShapeError& e) {
    throw CellShapeError(step + e.path(), e.problem());
  }
}
// An integer of JSON within [lo, hi].
long long integerIn(const Json& j, long long lo, long long hi);
}  // namespace detail

Json encode(double value);
void decode(const Json& j, double& value);
inline Json encode(bool value) { return value; }
inline void decode(const Json& j, bool& value) {
  if (!j.is_boolean()) detail::wrongShape(j, "true or false");
  value = j.get<bool>();
}
inline Json encode(int value) { return value; }
inline void decode(const Json& j, int& value) {
  value = static_cast<int>(detail::integerIn(j, std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
}
inline Json encode(long value) { return value; }
inline void decode(const Json& j, long& value) {
  value = static_cast<long>(detail::integerIn(j, std::numeric_limits<long>::min(), std::numeric_limits<long>::max()));
}
inline Json encode(const std::string& value) { return value; }
inline void decode(const Json& j, std::string& value) {
  if (!j.is_string()) detail::wrongShape(j, "a string");
  value = j.get<std::string>();
}

template <class E, std::enable_if_t<std::is_enum_v<E>, int> = 0>
Json encode(E value) {
  return static_cast<int>(value);
}
template <class E, std::enable_if_t<std::is_enum_v<E>, int> = 0>
void decode(const Json& j, E& value) {
  int raw = 0;
  decode(j, raw);
  value = static_cast<E>(raw);
}

// A struct with fields(io, value): an object of its named fields.
struct FieldEncoder;
struct FieldDecoder;
template <class T>
auto encode(const T& value) -> decltype(fields(std::declval<FieldEncoder&>(), const_cast<T&>(value)), Json());
template <class T>
auto decode(const Json& j, T& value) -> decltype(fields(std::declval<FieldDecoder&>(), value), void());

template <class T>
Json encode(const std::vector<T>& values);
template <class T>
void decode(const Json& j, std::vector<T>& values);
template <class A, class B>
Json encode(const std::pair<A, B>& value);
template <class A, class B>
void decode(const Json& j, std::pair<A, B>& value);

template <class T>
Json encode(const std::vector<T>& values) {
  Json j = Json::array();
  for (const T& v : values) j.push_back(encode(v));
  return j;
}
template <class T>
void decode(const Json& j, std::vector<T>& values) {
  if (!j.is_array()) detail::wrongShape(j, "an array");
  values.assign(j.size(), T{});
  for (std::size_t k = 0; k < values.size(); ++k)
    detail::within("[" + std::to_string(k) + "]", [&] { decode(j[k], values[k]); });
}
template <class A, class B>
Json encode(const std::pair<A, B>& value) {
  return Json::array({encode(value.first), encode(value.second)});
}
template <class A, class B>
void decode(const Json& j, std::pair<A, B>& value) {
  if (!j.is_array() || j.size() != 2) detail::wrongShape(j, "an array of 2 values");
  detail::within("[0]", [&] { decode(j[0], value.first); });
  detail::within("[1]", [&] { decode(j[1], value.second); });
}

struct FieldEncoder {
  Json object = Json::object();
  template <class T>
  void operator()(const char* name, const T& value) {
    object[name] = encode(value);
  }
};
struct FieldDecoder {
  const Json& object;
  std::size_t read = 0;  // fields found
  template <class T>
  void operator()(const char* name, T& value) {
    const auto found = object.find(name);
    if (found == object.end()) throw CellShapeError("", std::string("no field '") + name + "'");
    detail::within(std::string(".") + name, [&] { decode(*found, value); });
    ++read;
  }
};

template <class T>
auto encode(const T& value) -> decltype(fields(std::declval<FieldEncoder&>(), const_cast<T&>(value)), Json()) {
  FieldEncoder io;
  fields(io, const_cast<T&>(value));
  return std::move(io.object);
}
template <class T>
auto decode(const Json& j, T& value) -> decltype(fields(std::declval<FieldDecoder&>(), value), void()) {
  if (!j.is_object()) detail::wrongShape(j, "an object");
  FieldDecoder io{j};
  fields(io, value);
  if (io.read != j.size()) detail::wrongShape(j, "an object of " + std::to_string(io.read) + " fields, no more");
}

}  // namespace lab
