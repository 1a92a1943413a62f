// The input handlers GLUT's callbacks and the script both call: ImGui first,
// then the demo's keys, mouse tools and camera.
#include <GL/freeglut.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <new>
#include <stdexcept>

#include "app.h"

namespace demo {

const std::vector<App::KeyBinding>& App::keyBindings() {
  static const std::vector<KeyBinding> table = {
      {"i", "i", "next integrator, keeping the state", &App::cycleIntegrators},
      {"+=", "+ / -", "double / halve dt", &App::doubleDt},
      {"-_", nullptr, nullptr, &App::halveDt},
      {" ", "space", "pause / run (held: drag to pan)", &App::togglePause},
      {".", ".", "one step (pauses)", &App::stepOnce},
      {"r", "r", "reset the scene", &App::resetScene},
      {"b", "b", "rewind about one second (every pane to one time)", &App::rewind},
      {"a", "a", "frame all: fit the view to the particles", &App::frameAll},
      {"A", "A", "the scene's own view: the camera reset, the scene running on", &App::sceneView},
      {"f", "f", "force arrows on / off (colour per force type)", &App::toggleForces},
      {"c", "c", "constraint drawing on / off (the constraints always act)", &App::toggleConstraints},
      {"g", "g", "closed-form ghost on / off (oscillator, pendulum)", &App::toggleGhost},
      {"w", "w", "wind on / off (cloth, hair; the panel sets it)", &App::toggleWind},
      {"t", "t", "tearing on / off: springs stretched too far break (the panel sets the strain)", &App::toggleTearing},
      {"v", "v", "compare mode: 2, 3, 4 panes, then back to 1", &App::cyclePaneCount},
      {"l", "l", "lockstep: one step per frame / fixed time per frame", &App::toggleLockstep},
      {"p", "p", "control panel on / off", &App::togglePanel},
      {"e", "e", "build mode: add, move, delete; save as a scene file (keys in the panel)", &App::toggleBuildMode},
      {"k", "k", "screenshot: a PNG of the window (into --record's directory, else the working directory)",
       &App::requestScreenshot},
      {"h", "h", "this help", &App::toggleHelp},
      {"\x1bq", "Esc / q", "quit (Esc first closes an open list)", &App::requestQuit},
  };
  return table;
}

// Every action runs through here: an exception (a dt that would reach 0 or
// infinity, a scene file edited into an invalid one, a mass too large for the
// mouse joint, memory running out) becomes a message on screen and the demo
// runs on with its state as it was.
void App::guarded(const std::function<void()>& action) {
  try {
    action();
  } catch (const std::bad_alloc&) {
    setError("out of memory: the action was not done");
  } catch (const std::exception& e) {
    setError(e.what());
  }
}

void App::showError(const std::string& message) { setError(message); }

// --- ImGui first ---------------------------------------------------------

void App::inputKey(unsigned char key) {
  if (imguiReady_) {
    ImGuiIO& io = ImGui::GetIO();
    if (key >= 32) io.AddInputCharacter(key);
    io.KeysDown[key] = true;
    if (io.WantTextInput) return;
    // Esc with a list open closes the list (its window does it next frame).
    if (key == 27 && ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId)) {
      closePopups_ = true;
      return;
    }
  }
  if (key == ' ') {
    if (spaceHeld_) return;  // the window system's key repeat
    spaceHeld_ = true;
    spaceDragged_ = false;
  }
  guarded([&] { keyboard(key); });
}

void App::inputKeyUp(unsigned char key) {
  if (imguiReady_) ImGui::GetIO().KeysDown[key] = false;
  if (key == ' ') spaceHeld_ = false;
}

void App::inputMouse(int button, int state, int x, int y, bool shift) {
  if (imguiReady_) {
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = ImVec2(static_cast<float>(x), static_cast<float>(y));
    io.KeyShift = shift;
    const int index = button == GLUT_LEFT_BUTTON ? 0 : button == GLUT_RIGHT_BUTTON ? 1 : button == GLUT_MIDDLE_BUTTON ? 2 : -1;
    if (index >= 0) io.MouseDown[index] = state == GLUT_DOWN;
    // Releases always reach the demo so that a drag never sticks.
    if (state == GLUT_DOWN && io.WantCaptureMouse) return;
  }
  guarded([&] { mouse(button, state, x, y, shift); });
}

void App::inputMotion(int x, int y) {
  if (imguiReady_) ImGui::GetIO().MousePos = ImVec2(static_cast<float>(x), static_cast<float>(y));
  guarded([&] { motion(x, y); });
}

void App::inputPassiveMotion(int x, int y) {
  if (imguiReady_) ImGui::GetIO().MousePos = ImVec2(static_cast<float>(x), static_cast<float>(y));
  if (build_.active()) guarded([&] { buildMotion(x, y); });
}

void App::inputWheel(int direction, int x, int y) {
  if (imguiReady_) {
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = ImVec2(static_cast<float>(x), static_cast<float>(y));
    io.MouseWheel += direction > 0 ? 1.0f : direction < 0 ? -1.0f : 0.0f;
    if (io.WantCaptureMouse) return;
  }
  const int k = paneAt(x, y);
  if (k < 0 || direction == 0) return;
  const Eigen::Vector2d at = paneViews()[k].toWorld(x, y);
  camera_.zoom(std::pow(Camera::wheelFactor, direction), at);  // a script may turn several clicks at once
}

// --- the demo's keys and mouse tools ---------------------------------------

void App::keyboard(unsigned char key) {
  if (build_.active() && buildKeyboard(key)) return;
  for (const SceneKey& k : sceneKeys())
    if (k.key == key) {
      chooseScene(k.choice);
      return;
    }
  for (const KeyBinding& binding : keyBindings())
    if (key != 0 && std::strchr(binding.keys, key)) {
      (this->*binding.action)();
      return;
    }
}

// A scene from the keys or the panel's list: it keeps the preset in use, and
// compare mode keeps its panes' integrators.
void App::chooseScene(SceneChoice choice) {
  choice.preset = scene_.preset;
  loadScene(choice, panes_.size() > 1);
}

void App::toggleLockstep() {
  stepMode_ = stepMode_ == StepMode::Lockstep ? StepMode::FixedTime : StepMode::Lockstep;
  setStatus(stepMode_ == StepMode::Lockstep ? "lockstep: one step per frame" : "fixed simulated time per frame");
}

void App::mouse(int button, int state, int x, int y, bool shift) {
  if (build_.active() && buildMouse(button, state, x, y)) return;
  if (state == GLUT_UP) {
    if (tool_ == MouseTool::Drag)
      for (auto& pane : panes_) pane->release();
    if (tool_ == MouseTool::Pin && pinWasPinned_ && !pinMoved_)
      for (auto& pane : panes_) pane->setPinned(toolParticle_, false);
    tool_ = MouseTool::None;
    panning_ = false;
    return;
  }
  const int k = paneAt(x, y);
  if (k < 0) return;
  // Middle button, or left with space held: pan. Space pressed for a pan
  // does not pause, so its toggle is taken back.
  if (button == GLUT_MIDDLE_BUTTON || (button == GLUT_LEFT_BUTTON && spaceHeld_)) {
    if (spaceHeld_ && !spaceDragged_) {
      spaceDragged_ = true;
      togglePause();
    }
    panning_ = true;
    panX_ = x;
    panY_ = y;
    return;
  }
  if (button != GLUT_LEFT_BUTTON && button != GLUT_RIGHT_BUTTON) return;
  const ViewTransform view = paneViews()[k];
  const Eigen::Vector2d world = view.toWorld(x, y);
  const bool pinTool = button == GLUT_RIGHT_BUTTON || shift;
  // The same particle index in every pane: the panes run the same scene.
  const std::optional<int> particle =
      panes_[k]->particleNear(world, mouseSettings_.pickPixels / view.pixelsPerUnit, !pinTool);
  if (!particle) return;  // a press in empty space does nothing
  toolParticle_ = *particle;
  toolPane_ = k;
  pressX_ = x;
  pressY_ = y;
  if (!disturbedAt_) disturbedAt_ = panes_[k]->system().time();
  if (pinTool) {
    tool_ = MouseTool::Pin;
    pinWasPinned_ = panes_[k]->system().pinned(*particle);
    pinMoved_ = false;
    for (auto& pane : panes_) pane->setPinned(*particle, true);
    return;
  }
  // Every pane's joint first, so that a mass the joint cannot hold leaves no pane grabbed.
  for (auto& pane : panes_) pane->grabGains(*particle, mouseSettings_.joint);
  for (auto& pane : panes_) pane->grab(*particle, world, mouseSettings_.joint);
  tool_ = MouseTool::Drag;
  grabbedOnce_ = true;
}

void App::motion(int x, int y) {
  if (panning_) {
    const double ppu = paneViews().front().pixelsPerUnit;
    camera_.pan(Eigen::Vector2d(-(x - panX_) / ppu, (y - panY_) / ppu));
    panX_ = x;
    panY_ = y;
    return;
  }
  if (build_.active()) buildMotion(x, y);
  if (tool_ == MouseTool::None) return;
  const Eigen::Vector2d world = paneViews()[toolPane_].toWorld(x, y);
  for (auto& pane : panes_) {
    if (tool_ == MouseTool::Drag) pane->moveGrab(world);
    else pane->placePinned(toolParticle_, world);
  }
  // A click that wobbles by a pixel or two is still a click (it unpins).
  if (std::abs(x - pressX_) + std::abs(y - pressY_) > 3) pinMoved_ = true;
}

void App::frameAll() {
  Eigen::Vector2d lo, hi, a, b;
  bool any = false;
  for (const auto& pane : panes_)
    if (particleBounds(pane->system(), a, b)) {
      lo = any ? lo.cwiseMin(a) : a;
      hi = any ? hi.cwiseMax(b) : b;
      any = true;
    }
  if (!any) {
    setStatus("no particle with a finite position to frame");
    return;
  }
  camera_.frame(lo, hi);
  setStatus("framed all particles (A: the scene's own view; r resets the scene and its view)");
}

void App::sceneView() {
  camera_.reset(panes_.front()->scene().viewMin, panes_.front()->scene().viewMax);
  setStatus("the scene's own view (the scene runs on; r resets it)");
}

}  // namespace demo
