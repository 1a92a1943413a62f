#pragma once
// One running copy of a scene, as shown in one pane: the built system, its
// integrator and dt, the user's mouse spring and pins, a rewind history and a
// divergence watch. No OpenGL here.
#include <memory>
#include <optional>
#include <string>

#include "particles/forces/mouse_spring.h"
#include "particles/integrator.h"
#include "rewind_buffer.h"
#include "scene.h"
#include "trace.h"

namespace demo {

// How a frame advances the simulation.
enum class StepMode {
  FixedTime,  // a fixed simulated time per frame, in as many dt substeps as it takes
  Lockstep,   // exactly one dt step per frame (the seed report's loop)
};

// When a state counts as diverged: non-finite, or a constraint violated by
// more than its own length scale (or, for one without, by more than the
// view), or a particle flung far outside the view.
struct DivergenceLimits {
  double relativeConstraintError = 1.0;  // max |C| / length scale
  double constraintErrorInViews = 1.0;   // max |C| in units of the view's diagonal
  double distanceInViews = 1000.0;       // |x| in units of the view's diagonal
};

// At most this many steps per frame: with a tiny dt the simulation then runs
// slower than the fixed simulated time per frame instead of freezing the window.
constexpr int maxSubstepsPerFrame = 2000;

// Measurements of the last frame, for the HUD.
struct FrameStats {
  int substeps = 0;
  bool capped = false;        // maxSubstepsPerFrame cut the frame's simulated time short
  double simulationMs = 0.0;  // wall time spent stepping this frame
};

class Simulation {
 public:
  Simulation(scenes::Scene scene, int integratorIndex, double dt);

  // --- stepping: called once per frame ------------------------------------
  // Advances by frameTime (or one step in lockstep), stopping at once when the
  // state diverges; records history and the trace.
  void advanceFrame(double frameTime, StepMode mode);
  void stepOnce();  // one dt step (the '.' key)

  // --- settings -----------------------------------------------------------
  void setIntegrator(int index);  // keeps the state
  int integratorIndex() const { return integratorIndex_; }
  const char* integratorName() const;
  void setDt(double dt);  // throws for dt ≤ 0 or NaN
  double dt() const { return dt_; }

  // --- the user's hand ----------------------------------------------------
  // Nearest particle to `world` within `radius` (world units), movable only or any.
  std::optional<int> particleNear(const Eigen::Vector2d& world, double radius, bool movableOnly) const;
  void grab(int particle, const Eigen::Vector2d& target, double stiffness, double damping);
  void moveGrab(const Eigen::Vector2d& target);
  void release();
  const particles::MouseSpringForce* mouseSpring() const { return spring_; }
  void setPinned(int particle, bool pinned);
  void placePinned(int particle, const Eigen::Vector2d& position);  // drags a pinned particle

  // --- divergence and rewind ------------------------------------------------
  std::optional<double> divergedAt() const { return divergedAt_; }
  // The simulated time it stopped at if diverged, else its clock.
  double timeReached() const { return divergedAt_ ? *divergedAt_ : system().time(); }
  // Restores the newest recorded state at or before `time` (the oldest kept
  // if none is that old) and clears the divergence. Returns the time restored to.
  std::optional<double> rewindTo(double time);
  // Copies the dynamic state and pins of another simulation of the same scene.
  void copyStateFrom(const Simulation& other);

  // --- reading ------------------------------------------------------------
  const scenes::Scene& scene() const { return scene_; }
  particles::ParticleSystem& system() { return *scene_.system; }
  const particles::ParticleSystem& system() const { return *scene_.system; }
  const FrameStats& lastFrame() const { return lastFrame_; }
  const Trace& trace() const { return trace_; }
  long long steps() const { return steps_; }

 private:
  bool checkDiverged();
  void stepAndWatch();

  scenes::Scene scene_;
  std::unique_ptr<particles::Integrator> integrator_;
  int integratorIndex_;
  double dt_;
  double owedTime_ = 0.0;  // simulated time accumulated but not yet stepped
  long long steps_ = 0;
  particles::MouseSpringForce* spring_ = nullptr;  // owned by the system
  DivergenceLimits limits_;
  std::optional<double> divergedAt_;
  RewindBuffer history_;
  FrameStats lastFrame_;
  Trace trace_;
};

}  // namespace demo
