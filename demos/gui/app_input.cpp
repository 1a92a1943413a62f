// The input handlers GLUT's callbacks and the script both call.
#include <GL/freeglut.h>

#include <cmath>
#include <cstdlib>
#include <cstring>

#include "app.h"

namespace demo {

const std::vector<App::KeyBinding>& App::keyBindings() {
  static const std::vector<KeyBinding> table = {
      {"i", "i", "next integrator, keeping the state", &App::cycleIntegrators},
      {"+=", "+ / -", "double / halve dt", &App::doubleDt},
      {"-_", nullptr, nullptr, &App::halveDt},
      {" ", "space", "pause / run", &App::togglePause},
      {".", ".", "one step (pauses)", &App::stepOnce},
      {"r", "r", "reset the scene", &App::resetScene},
      {"b", "b", "rewind about one second", &App::rewind},
      {"f", "f", "force arrows on / off (colour per force type)", &App::toggleForces},
      {"c", "c", "constraints on / off", &App::toggleConstraints},
      {"v", "v", "compare mode: 2, 3, 4 panes, then back to 1", &App::cyclePaneCount},
      {"l", "l", "lockstep: one step per frame / fixed time per frame", &App::toggleLockstep},
      {"p", "p", "control panel on / off", &App::togglePanel},
      {"h", "h", "this help", &App::toggleHelp},
      {"\x1bq", "Esc / q", "quit", &App::requestQuit},
  };
  return table;
}

void App::keyboard(unsigned char key) {
  for (const SceneKey& k : sceneKeys())
    if (k.key == key) {
      SceneChoice choice = k.choice;
      choice.preset = scene_.preset;  // a new scene keeps the preset in use
      loadScene(choice, panes_.size() > 1);
      setStatus("scene: " + k.choice.label);
      return;
    }
  for (const KeyBinding& binding : keyBindings())
    if (key != 0 && std::strchr(binding.keys, key)) {
      (this->*binding.action)();
      return;
    }
}

void App::toggleLockstep() {
  stepMode_ = stepMode_ == StepMode::Lockstep ? StepMode::FixedTime : StepMode::Lockstep;
  setStatus(stepMode_ == StepMode::Lockstep ? "lockstep: one step per frame" : "fixed simulated time per frame");
}

void App::mouse(int button, int state, int x, int y, bool shift) {
  if (state == GLUT_UP) {
    if (tool_ == MouseTool::Drag)
      for (auto& pane : panes_) pane->release();
    if (tool_ == MouseTool::Pin && pinWasPinned_ && !pinMoved_)
      for (auto& pane : panes_) pane->setPinned(toolParticle_, false);
    tool_ = MouseTool::None;
    return;
  }
  if (button != GLUT_LEFT_BUTTON && button != GLUT_RIGHT_BUTTON) return;
  const int k = paneAt(x, y);
  if (k < 0) return;
  const ViewTransform view = paneViews()[k];
  const Eigen::Vector2d world = view.toWorld(x, y);
  const bool pinTool = button == GLUT_RIGHT_BUTTON || shift;
  // The same particle index in every pane: the panes run the same scene.
  const std::optional<int> particle =
      panes_[k]->particleNear(world, springSettings_.pickPixels / view.pixelsPerUnit, !pinTool);
  if (!particle) return;  // a press in empty space does nothing
  toolParticle_ = *particle;
  toolPane_ = k;
  pressX_ = x;
  pressY_ = y;
  if (pinTool) {
    tool_ = MouseTool::Pin;
    pinWasPinned_ = panes_[k]->system().pinned(*particle);
    pinMoved_ = false;
    for (auto& pane : panes_) pane->setPinned(*particle, true);
    return;
  }
  tool_ = MouseTool::Drag;
  for (auto& pane : panes_) {
    const double mass = pane->system().masses()[*particle];
    const double stiffness = springSettings_.stiffness(mass);
    const double damping =
        springSettings_.criticalDamping ? 2.0 * std::sqrt(stiffness * mass) : springSettings_.damping;
    pane->grab(*particle, world, stiffness, damping);
  }
}

void App::motion(int x, int y) {
  if (tool_ == MouseTool::None) return;
  const Eigen::Vector2d world = paneViews()[toolPane_].toWorld(x, y);
  for (auto& pane : panes_) {
    if (tool_ == MouseTool::Drag) pane->moveGrab(world);
    else pane->placePinned(toolParticle_, world);
  }
  // A click that wobbles by a pixel or two is still a click (it unpins).
  if (std::abs(x - pressX_) + std::abs(y - pressY_) > 3) pinMoved_ = true;
}

}  // namespace demo
