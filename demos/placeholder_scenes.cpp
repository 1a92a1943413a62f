// TEMPORARY stand-in for the scene table of branch `scenes` (issue 4), so the
// GUI can be developed before it lands. Deleted when `main` brings the real one.
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "particles/constraints/circular_wire.h"
#include "particles/constraints/line.h"
#include "particles/constraints/rod.h"
#include "particles/forces/angular_spring.h"
#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "scene.h"

namespace scenes {

using namespace particles;

SceneParams::SceneParams(const std::vector<ParamSpec>& specs,
                         const std::map<std::string, std::string>& values) {
  for (const ParamSpec& s : specs) {
    values_[s.name] = s.defaultValue;
    validNames_ += (validNames_.empty() ? "" : ", ") + s.name;
  }
  for (const auto& [k, v] : values) {
    if (!values_.count(k)) throw std::invalid_argument("unknown parameter '" + k + "' (valid: " + validNames_ + ")");
    values_[k] = v;
  }
}
const std::string& SceneParams::raw(const std::string& name) const { return values_.at(name); }
double SceneParams::number(const std::string& name) const { return std::stod(raw(name)); }
int SceneParams::integer(const std::string& name) const { return std::stoi(raw(name)); }
const std::string& SceneParams::text(const std::string& name) const { return raw(name); }

namespace {
Scene cloth(const SceneParams& p) {
  Scene s;
  s.name = "cloth";
  s.system = std::make_unique<ParticleSystem>();
  ParticleSystem& sys = *s.system;
  const int w = p.integer("width"), h = p.integer("height");
  const double rest = 0.05;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) sys.addParticle({-0.25 + c * rest, 0.8 - r * rest}, 0.2);
  auto id = [w](int r, int c) { return r * w + c; };
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      if (c + 1 < w) sys.addForce(std::make_unique<SpringForce>(id(r, c), id(r, c + 1), rest, 0.9, 0.6));
      if (r + 1 < h) sys.addForce(std::make_unique<SpringForce>(id(r, c), id(r + 1, c), rest, 0.9, 0.6));
      if (p.integer("links") == 8 && r + 1 < h && c + 1 < w) {
        sys.addForce(std::make_unique<SpringForce>(id(r, c), id(r + 1, c + 1), rest * std::sqrt(2.0), 0.9, 0.6));
        sys.addForce(std::make_unique<SpringForce>(id(r, c + 1), id(r + 1, c), rest * std::sqrt(2.0), 0.9, 0.6));
      }
    }
  for (int c = 0; c < w; ++c) sys.addConstraint(std::make_unique<LineConstraint>(id(0, c), Eigen::Vector2d(0, 0.8), 0.0));
  sys.addForce(std::make_unique<GravityForce>(Eigen::Vector2d(0, -0.05)));
  Wall big; big.min = {-0.9, -0.9}; big.max = {-0.3, 0.3};
  Wall nail; nail.min = {0.3, 0.2}; nail.max = {0.35, 0.25};
  sys.addWall(big);
  sys.addWall(nail);
  return s;
}

Scene testChain(const SceneParams& p) {
  Scene s;
  s.name = "test-chain";
  s.system = std::make_unique<ParticleSystem>();
  ParticleSystem& sys = *s.system;
  const int n = p.integer("cl");
  const double len = 1.6 / n;
  for (int i = 0; i < n; ++i) sys.addParticle({-0.8 + i * len, 0.5}, 1.0);
  sys.setPinned(0, true);
  for (int i = 0; i + 1 < n; ++i) sys.addConstraint(std::make_unique<RodConstraint>(i, i + 1, len));
  sys.addForce(std::make_unique<GravityForce>(Eigen::Vector2d(0, -0.05)));
  return s;
}

Scene hair(const SceneParams& p) {
  Scene s;
  s.name = "hair";
  s.system = std::make_unique<ParticleSystem>();
  ParticleSystem& sys = *s.system;
  const int curls = p.integer("curls"), n = 25;
  for (int k = 0; k < curls; ++k) {
    const double x0 = -0.6 + 1.2 * k / std::max(1, curls - 1);
    const int first = sys.size();
    for (int i = 0; i < n; ++i) {
      sys.addParticle({x0 + 0.03 * std::sin(i * 1.5), 0.7 - 0.04 * i}, 0.1);
      sys.setCollidable(first + i, 0.015);
    }
    for (int i = 0; i + 1 < n; ++i) sys.addForce(std::make_unique<SpringForce>(first + i, first + i + 1, 0.04, 5, 0.5));
    for (int i = 0; i + 2 < n; ++i)
      sys.addForce(std::make_unique<AngularSpringForce>(first + i, first + i + 1, first + i + 2, M_PI / 2, 1e-3, 3e-3));
    sys.addConstraint(std::make_unique<LineConstraint>(first, Eigen::Vector2d(0, 0.7), 0.0));
  }
  sys.addForce(std::make_unique<GravityForce>(Eigen::Vector2d(0, -0.05)));
  return s;
}

Scene wire(const SceneParams&) {
  Scene s;
  s.name = "wire";
  s.system = std::make_unique<ParticleSystem>();
  s.system->addParticle({0.5, 0.0}, 1.0);
  s.system->addConstraint(std::make_unique<CircularWireConstraint>(0, Eigen::Vector2d(0, 0), 0.5));
  s.system->addForce(std::make_unique<GravityForce>(Eigen::Vector2d(0, -0.05)));
  return s;
}
}  // namespace

const std::vector<SceneInfo>& sceneTable() {
  static const std::vector<SceneInfo> table = {
      {"cloth", "cloth curtain", {{"width", "10", "particles"}, {"height", "10", "particles"}, {"links", "4", "4|8"}}, cloth},
      {"hair", "curls", {{"curls", "6", "count"}}, hair},
      {"wire", "bead on a wire", {}, wire},
      {"test-chain", "rod chain", {{"cl", "20", "particles"}}, testChain},
  };
  return table;
}

Scene buildScene(const std::string& name, const std::map<std::string, std::string>& overrides) {
  for (const SceneInfo& info : sceneTable())
    if (name == info.name) return info.build(SceneParams(info.params, overrides));
  throw std::invalid_argument("unknown scene '" + name + "'");
}

}  // namespace scenes
