// The input handlers GLUT's callbacks and the script both call.
#include <GL/freeglut.h>

#include <cmath>
#include <cstdlib>

#include "app.h"

namespace demo {

void App::keyboard(unsigned char key) {
  for (const SceneKey& k : sceneKeys())
    if (k.key == key) {
      loadScene(k.choice, panes_.size() > 1);
      setStatus("scene: " + k.choice.label);
      return;
    }
  switch (key) {
    case 'i': cycleIntegrators(); break;
    case '+': case '=': scaleDt(2.0); break;
    case '-': case '_': scaleDt(0.5); break;
    case ' ': paused_ = !paused_; break;
    case '.': paused_ = true; stepRequested_ = true; break;
    case 'r': resetScene(); break;
    case 'b': rewind(); break;
    case 'f': drawOptions_.forces = !drawOptions_.forces; break;
    case 'c': drawOptions_.constraints = !drawOptions_.constraints; break;
    case 'h': showHelp_ = !showHelp_; break;
    case 'p': showPanel_ = !showPanel_; break;
    case 'l':
      stepMode_ = stepMode_ == StepMode::Lockstep ? StepMode::FixedTime : StepMode::Lockstep;
      setStatus(stepMode_ == StepMode::Lockstep ? "lockstep: one step per frame" : "fixed simulated time per frame");
      break;
    case 'v': setPaneCount(panes_.size() >= 4 ? 1 : static_cast<int>(panes_.size()) + 1); break;
    case 27: case 'q': quit_ = true; break;
    default: break;
  }
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
    const double damping = springSettings_.criticalDamping ? 2.0 * std::sqrt(springSettings_.stiffness * mass)
                                                           : springSettings_.damping;
    pane->grab(*particle, world, springSettings_.stiffness, damping);
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
