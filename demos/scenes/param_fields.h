#pragma once
// Scene parameters as plain structs with defaults. Each struct lists its fields
// once, in visit(name, field, help); from that list the table takes the names,
// defaults and help it shows, and buildScene fills the fields from --param
// overrides. Adding a parameter is one member and one visit line.
#include <string>
#include <vector>

#include "format_number.h"
#include "scene.h"

namespace scenes {

inline std::string formatParam(double value) { return formatNumber(value); }
std::string formatParam(int value);
inline std::string formatParam(const std::string& value) { return value; }

inline void readParam(const SceneParams& values, const char* name, double& field) { field = values.number(name); }
inline void readParam(const SceneParams& values, const char* name, int& field) { field = values.integer(name); }
inline void readParam(const SceneParams& values, const char* name, std::string& field) { field = values.text(name); }

template <class Params>
std::vector<ParamSpec> paramSpecs() {
  Params defaults;
  std::vector<ParamSpec> specs;
  defaults.visit([&](const char* name, const auto& field, const char* help) {
    specs.push_back({name, formatParam(field), help});
  });
  return specs;
}

// Every field from values (defaults where not overridden), then Params::validate().
template <class Params>
Params readParams(const SceneParams& values) {
  Params p;
  p.visit([&](const char* name, auto& field, const char*) { readParam(values, name, field); });
  p.validate();
  return p;
}

// Integer checks in the style of particles/check.h: the message names the
// parameter and its value.
void requireAtLeast(const char* name, int value, int minimum);

}  // namespace scenes
