#include <charconv>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "decimal_number.h"
#include "join_names.h"
#include "scene.h"
#include "scene_limits.h"
#include "scenes/param_fields.h"

namespace scenes {

std::string formatParam(int value) { return std::to_string(value); }

void requireAtLeast(const char* name, int value, int minimum) {
  if (value < minimum)
    throw std::invalid_argument(std::string(name) + " must be >= " + std::to_string(minimum) +
                                ", got " + std::to_string(value));
}

void requireWithinLimit(const std::string& what, long long count, long long limit) {
  if (count > limit)
    throw std::invalid_argument(what + " = " + std::to_string(count) + " exceeds the limit of " + std::to_string(limit));
}

const std::vector<PresetInfo>& presetTable() {
  static const std::vector<PresetInfo> table = {
      {kDefaultPreset, "real time in SI units: g = 9.81 m/s^2, metres, periods of 0.5-3 s"},
      {kSeedPreset, "the seed report's values (g = 0.05 on scenes about 1 unit across), as the laboratory uses"},
  };
  return table;
}

std::size_t presetIndex(const std::string& preset) {
  const std::vector<PresetInfo>& table = presetTable();
  for (std::size_t k = 0; k < table.size(); ++k)
    if (preset == table[k].name) return k;
  throw std::invalid_argument("unknown preset '" + preset + "' (valid: " + joinNames(table) + ")");
}

SceneParams::SceneParams(const std::vector<ParamSpec>& specs, const std::map<std::string, std::string>& values,
                         const std::string& preset)
    : preset_(presetIndex(preset)) {
  for (const ParamSpec& spec : specs) values_[spec.name] = spec.values.at(preset_);
  validNames_ = specs.empty() ? "none" : joinNames(specs);
  for (const auto& [name, value] : values) {
    if (!values_.count(name))
      throw std::invalid_argument("unknown parameter '" + name + "' (valid: " + validNames_ + ")");
    values_[name] = value;
  }
}

const std::string& SceneParams::raw(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end())
    throw std::invalid_argument("unknown parameter '" + name + "' (valid: " + validNames_ + ")");
  return it->second;
}

double SceneParams::number(const std::string& name) const {
  const std::string& text = raw(name);
  double value = 0.0;
  try {
    value = readDecimalNumber(text);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("parameter '" + name + "': " + e.what());
  }
  if (!std::isfinite(value))
    throw std::invalid_argument("parameter '" + name + "' must be a finite number, got '" + text +
                                "' (valid parameters: " + validNames_ + ")");
  return value;
}

int SceneParams::integer(const std::string& name) const {
  const std::string& text = raw(name);
  int value = 0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || result.ec != std::errc() || result.ptr != text.data() + text.size())
    throw std::invalid_argument("parameter '" + name + "' must be an integer, got '" + text +
                                "' (valid parameters: " + validNames_ + ")");
  return value;
}

const std::string& SceneParams::text(const std::string& name) const { return raw(name); }

}  // namespace scenes
