// The demo's logic without its window, fuzzed (the sanitizer build runs this,
// as it cannot run the demo): build mode's tools, gestures, edits, undo and
// redo on documents of every built-in scene, each committed edit shown as a
// new Simulation, and that simulation stepped, rewound and handled as the
// mouse handles it (pins placed, particles grabbed and released, integrator,
// dt, wind and tearing changed). The glue below does what App's actions do
// (build_actions.cpp, app_input.cpp) with the same classes; a refused action
// may throw std::invalid_argument or SceneFileError (the App shows those in
// its top bar), anything else, or a fault, fails.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <string>

#include "build_mode.h"
#include "particles/integrator.h"
#include "scene.h"
#include "scene_document.h"
#include "scene_file/scene_file.h"
#include "simulation.h"
#include "test_support.h"

namespace demo {
namespace {

class DemoLogic {
 public:
  explicit DemoLogic(unsigned seed) : rng_(seed) {}

  // One random action; lastAction() names it, for a failure's message.
  void act() {
    struct Action {
      const char* name;
      void (DemoLogic::*run)();
    };
    static const Action actions[] = {
        {"start from a scene", &DemoLogic::startFrom}, {"a tool's gesture", &DemoLogic::gesture},
        {"a tool's gesture", &DemoLogic::gesture},     {"a tool's gesture", &DemoLogic::gesture},
        {"Enter (finish clicks)", &DemoLogic::finishClicks}, {"undo or redo", &DemoLogic::undoOrRedo},
        {"edit a field", &DemoLogic::editField},        {"delete the selection", &DemoLogic::deleteSelection},
        {"step", &DemoLogic::step},                     {"step", &DemoLogic::step},
        {"pin and place", &DemoLogic::pin},             {"grab, move, release", &DemoLogic::grab},
        {"integrator, dt, wind, tearing", &DemoLogic::settings}, {"rewind", &DemoLogic::rewind},
    };
    const Action& action = actions[pick(static_cast<int>(std::size(actions)))];
    last_ = action.name;
    (this->*action.run)();
  }
  const std::string& lastAction() const { return last_; }

 private:
  int pick(int n) { return static_cast<int>(rng_() % static_cast<unsigned>(n)); }
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  Eigen::Vector2d somewhere() {
    const particles::ParticleSystem* s = pane_ ? &pane_->system() : nullptr;
    if (s && s->size() > 0 && pick(2) == 0)  // at a particle, or near it
      return s->position(pick(s->size())) + Eigen::Vector2d(uniform(-0.02, 0.02), uniform(-0.02, 0.02));
    return {uniform(-1.2, 1.2), uniform(-1.2, 1.2)};
  }

  // App::startBuildFrom and showBuiltScene.
  void startFrom() {
    const auto& table = scenes::sceneTable();
    Json document = pick(4) == 0 ? emptyDocument() : documentOf(scenes::buildScene(table[pick(static_cast<int>(table.size()))].name));
    scenes::Scene scene = buildDocument(document);
    build_.history.push(std::move(document), "start");
    build_.selection.reset();
    build_.cancelGesture();
    show(std::move(scene));
  }
  void show(scenes::Scene scene) {
    const int integrator = integratorIndexByName(scene.integrator);
    const double dt = scene.dt;
    const particles::IntegratorSettings settings = scene.integratorSettings;
    pane_ = std::make_unique<Simulation>(std::move(scene), integrator, dt);
    pane_->setIntegratorSettings(settings);
  }
  void ensureStarted() {
    if (build_.history.empty()) startFrom();
  }

  // App::buildMouse's press and release, and runBuildTool.
  void gesture() {
    ensureStarted();
    if (pick(3) == 0) build_.selectTool(static_cast<std::size_t>(pick(static_cast<int>(buildTools().size()))));
    if (pick(4) == 0) build_.grid = pick(2) ? 0.0 : 0.1;
    const double radius = 0.03;
    build_.press(build_.pointAt(somewhere(), pane_->system(), radius, false));
    if (pick(2)) build_.moveTo(somewhere());
    if (const auto points = build_.release(build_.pointAt(somewhere(), pane_->system(), radius, true), radius))
      runTool(*points);
  }
  void finishClicks() {
    ensureStarted();
    if (const auto points = build_.finishClicks()) runTool(*points);
  }
  void runTool(const std::vector<BuildPoint>& points) {
    Json next = build_.history.current();
    std::optional<ObjectRef> selection = build_.selection;
    const std::size_t tool = build_.toolIndex();
    ToolContext context{next, pane_->system(), build_.particleFields(), build_.fields(tool), 0.03, selection};
    const std::string what = build_.tool().apply(context, points);
    if (!what.empty()) commit(std::move(next), what);
    build_.selection = selection;
  }
  void commit(Json document, const std::string& what) {
    scenes::Scene scene = buildDocument(document);  // a refused edit changes nothing
    build_.history.push(std::move(document), what);
    show(std::move(scene));
  }

  void undoOrRedo() {
    ensureStarted();
    if (pick(2) ? build_.history.canUndo() : !build_.history.canRedo()) {
      if (!build_.history.canUndo()) return;
      build_.history.undo();
    } else {
      build_.history.redo();
    }
    build_.selection.reset();
    build_.cancelGesture();
    show(buildDocument(build_.history.current()));
  }

  void editField() {
    ensureStarted();
    static const char* const fields[] = {"position", "mass", "radius", "pinned", "stiffness", "restLength", "length",
                                         "velocity", "restitution", "friction", "dt", "integrator", "name", "min"};
    static const char* const values[] = {"1", "0", "-1", "0.5", "1e308", "5e-324", "0x10", "nan", "[0,0]",
                                         "[1e300,-1e300]", "[0.1,0.2]", "true", "\"text\"", "{}", "[]", "null", "rk4"};
    const ObjectRef ref = build_.selection.value_or(ObjectRef{});
    Json next = build_.history.current();
    if (!ref.isScene() && !refersToObject(next, ref)) return;
    setField(next, ref, fields[pick(static_cast<int>(std::size(fields)))], parseFieldValue(values[pick(static_cast<int>(std::size(values)))]));
    commit(std::move(next), "set");
  }

  void deleteSelection() {
    ensureStarted();
    if (!build_.selection || !refersToObject(build_.history.current(), *build_.selection)) return;
    Json next = build_.history.current();
    deleteObject(next, *build_.selection);
    commit(std::move(next), "delete");
    build_.selection.reset();
  }

  void step() {
    ensureStarted();
    for (int k = 0, n = 1 + pick(4); k < n; ++k) pane_->stepOnce();
    pane_->endFrame(false);
  }

  // The pin tool: a particle of the pane on screen, pinned and placed.
  void pin() {
    ensureStarted();
    const int n = pane_->system().size();
    if (n == 0) return;
    const int i = pick(n);
    pane_->setPinned(i, true);
    pane_->placePinned(i, somewhere());
    if (pick(2)) pane_->setPinned(i, false);
  }
  void grab() {
    ensureStarted();
    const int n = pane_->system().size();
    if (n == 0) return;
    const int i = pick(n);
    if (!pane_->system().pinned(i)) pane_->grab(i, somewhere(), particles::MouseJointSettings{});
    pane_->moveGrab(somewhere());
    pane_->stepOnce();
    if (pick(2)) pane_->release();
  }
  void settings() {
    ensureStarted();
    switch (pick(4)) {
      case 0: pane_->setIntegrator(pick(static_cast<int>(particles::integratorTable().size()))); break;
      case 1: pane_->setDt(std::pow(10.0, uniform(-6.0, -1.0))); break;
      case 2: {
        particles::WindSettings wind;
        wind.speed = uniform(0.0, 20.0);
        pane_->setWind(pick(3) ? std::optional<particles::WindSettings>(wind) : std::nullopt);
        break;
      }
      default: pane_->setTearStrain(uniform(0.0, 1.0));
    }
  }
  void rewind() {
    ensureStarted();
    pane_->rewindTo(pick(20));
  }

  std::mt19937 rng_;
  std::string last_;
  BuildMode build_;
  std::unique_ptr<Simulation> pane_;
};

// A new dt or integrator while a particle is held sets the joint's gains
// again and keeps its target (the retune read the target of the spring it
// had just removed: a use after free, which the sanitizer build reports).
TEST(DemoLogic, ANewDtOrIntegratorWhileAParticleIsHeldKeepsItsTarget) {
  scenes::Scene scene = scenes::buildScene("pendulum");
  Simulation pane(std::move(scene), integratorIndexByName("rk4"), 0.01);
  const Eigen::Vector2d target(0.3, -0.2);
  pane.grab(0, pane.system().position(0), particles::MouseJointSettings{});
  pane.moveGrab(target);
  pane.setDt(0.005);
  ASSERT_NE(pane.mouseSpring(), nullptr);
  EXPECT_EQ(pane.mouseSpring()->target(), target);
  pane.setIntegrator(integratorIndexByName("symplectic-euler"));
  ASSERT_NE(pane.mouseSpring(), nullptr);
  EXPECT_EQ(pane.mouseSpring()->target(), target);
}

constexpr int kActions = test_support::kSanitizerBuild ? 1500 : 4000;

TEST(DemoLogicFuzz, RandomEditsGesturesStepsAndPinsNeverFault) {
  DemoLogic logic(20261221);
  int refused = 0;
  for (int k = 0; k < kActions; ++k) {
    try {
      logic.act();
    } catch (const std::invalid_argument&) {
      ++refused;
    } catch (const scenes::SceneFileError&) {
      ++refused;
    } catch (const std::exception& e) {
      FAIL() << "action " << k << " (" << logic.lastAction() << "): " << e.what();
    }
  }
  EXPECT_GT(refused, 0);
}

}  // namespace
}  // namespace demo
