#pragma once
// Cell results as JSON (lab/cells.h). Each result type lists its fields once,
// in a `fields(io, value)` function beside it; encode and decode walk that
// list. Every value is kept exactly: finite doubles as JSON numbers (written
// as the shortest text that reads back to the same double), NaN and ±inf —
// which JSON lacks — as the strings "nan", "inf" and "-inf".
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace lab {

using Json = nlohmann::json;

Json encode(double value);
void decode(const Json& j, double& value);
inline Json encode(bool value) { return value; }
inline void decode(const Json& j, bool& value) { value = j.get<bool>(); }
inline Json encode(int value) { return value; }
inline void decode(const Json& j, int& value) { value = j.get<int>(); }
inline Json encode(long value) { return value; }
inline void decode(const Json& j, long& value) { value = j.get<long>(); }
inline Json encode(const std::string& value) { return value; }
inline void decode(const Json& j, std::string& value) { value = j.get<std::string>(); }

template <class E, std::enable_if_t<std::is_enum_v<E>, int> = 0>
Json encode(E value) {
  return static_cast<int>(value);
}
template <class E, std::enable_if_t<std::is_enum_v<E>, int> = 0>
void decode(const Json& j, E& value) {
  value = static_cast<E>(j.get<int>());
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
  values.assign(j.size(), T{});
  for (std::size_t k = 0; k < values.size(); ++k) decode(j.at(k), values[k]);
}
template <class A, class B>
Json encode(const std::pair<A, B>& value) {
  return Json::array({encode(value.first), encode(value.second)});
}
template <class A, class B>
void decode(const Json& j, std::pair<A, B>& value) {
  decode(j.at(0), value.first);
  decode(j.at(1), value.second);
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
  template <class T>
  void operator()(const char* name, T& value) {
    decode(object.at(name), value);
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
  FieldDecoder io{j};
  fields(io, value);
}

}  // namespace lab
