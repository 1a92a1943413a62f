#pragma once
// Scene parameters as plain structs with defaults. Each struct lists its fields
// once, in visit(name, field, help); from that list the table takes the names,
// values and help it shows, and buildScene fills the fields from --param
// overrides. Adding a parameter is one member and one visit line.
//
// The presets (presetTable()): the member initialisers are preset "default";
// a static Params::seed() returns preset "seed", the seed report's values. A
// struct also carries the time step dt its scene runs with under each preset
// (not a --param: --dt and the demo's dt field set the step).
#include <string>
#include <vector>

#include "output/format_number.h"
#include "scene.h"

namespace scenes {

inline std::string formatParam(double value) { return output::formatNumber(value); }
std::string formatParam(int value);
inline std::string formatParam(const std::string& value) { return value; }

inline void readParam(const SceneParams& values, const char* name, double& field) { field = values.number(name); }
inline void readParam(const SceneParams& values, const char* name, int& field) { field = values.integer(name); }
inline void readParam(const SceneParams& values, const char* name, std::string& field) { field = values.text(name); }

// A Params struct under every preset, in presetTable() order.
template <class Params>
std::vector<Params> presetParams() {
  return {Params{}, Params::seed()};
}

template <class Params>
std::vector<ParamSpec> paramSpecs() {
  std::vector<ParamSpec> specs;
  for (Params preset : presetParams<Params>()) {
    std::size_t k = 0;
    preset.visit([&](const char* name, const auto& field, const char* help) {
      if (k == specs.size()) specs.push_back({name, {}, help});
      specs[k++].values.push_back(formatParam(field));
    });
  }
  return specs;
}

// The preset's struct with every field from values (the preset's value where
// not overridden), then Params::validate().
template <class Params>
Params readParams(const SceneParams& values) {
  Params p = presetParams<Params>().at(values.preset());
  p.visit([&](const char* name, auto& field, const char*) { readParam(values, name, field); });
  p.validate();
  return p;
}

// Integer checks in the style of particles/check.h: the message names the
// parameter and its value.
void requireAtLeast(const char* name, int value, int minimum);

}  // namespace scenes
