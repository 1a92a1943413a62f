#pragma once
// One running copy of a scene, as shown in one pane: the built system, its
// integrator and dt, the user's mouse spring and pins, a rewind history and a
// divergence watch. No OpenGL here.
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "particles/divergence.h"
#include "particles/forces/mouse_spring.h"
#include "particles/forces/wind.h"
#include "particles/grab.h"
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

// The demo's divergence limits (particles::checkDivergence): besides a
// non-finite state or a failed step, a constraint violated by more than its
// own length scale (or, for one without, by more than the view's diagonal),
// or a particle flung more than 1000 view diagonals away. No energy test.
particles::DivergenceLimits demoDivergenceLimits(const scenes::Scene& scene);

// Measurements of the last frame, for the HUD and the state log.
struct FrameStats {
  int substeps = 0;
  bool capped = false;         // the stepping budget ran out with steps still owed: the rest was dropped (slow motion)
  bool waited = false;         // it owed a step but the frame's budget was spent by the other panes first
  double simulationMs = 0.0;   // wall time spent stepping this frame
  double longestStepMs = 0.0;  // its longest single step this frame
};

// The signed area of a quad face, positive when its corners run counter-clockwise.
double faceArea(const particles::Phase& phase, const std::array<int, 4>& face);

// The table position of the integrator named `name`; throws for an unknown one.
int integratorIndexByName(const std::string& name);

class Simulation {
 public:
  Simulation(scenes::Scene scene, int integratorIndex, double dt);

  // --- stepping: a frame is beginFrame, takeStep while owesStep (as the
  // frame's budget allows, frame_budget.h), then endFrame ------------------
  // Owes frameTime more simulated time (or, in lockstep, one step).
  void beginFrame(double frameTime, StepMode mode);
  // A whole dt owed (or the lockstep step) and not stopped.
  bool owesStep() const;
  // One dt step, stopping at once when the state diverges; returns its wall time in ms.
  double takeStep();
  // Ends the frame: with budgetSpent, the simulated time still owed is
  // dropped (slow motion) instead of piling up behind a window that would
  // freeze; records history and the trace.
  void endFrame(bool budgetSpent);
  void stepOnce();  // one dt step (the '.' key)

  // --- settings -----------------------------------------------------------
  void setIntegrator(int index);  // keeps the state; clears a refusal
  int integratorIndex() const { return integratorIndex_; }
  const char* integratorName() const;
  // Settings of schemes that take them (dopri5's tolerance); kept across
  // integrator changes. Throws naming a bad field.
  void setIntegratorSettings(const particles::IntegratorSettings& settings);
  const particles::IntegratorSettings& integratorSettings() const { return integratorSettings_; }
  void setDt(double dt);  // throws for dt ≤ 0, NaN or infinite
  double dt() const { return dt_; }

  // --- the user's hand ----------------------------------------------------
  // Nearest particle to `world` within `radius` (world units), movable only or any.
  std::optional<int> particleNear(const Eigen::Vector2d& world, double radius, bool movableOnly) const;
  // The mouse joint's gains for grabbing `particle` now (particles/grab.h):
  // from its tied mass and attached stiffness, bounded by the integrator's
  // explicit force step at this dt. Throws naming the value when they overflow.
  particles::MouseSpringGains grabGains(int particle, const particles::MouseJointSettings& joint) const;
  // Attaches a mouse joint with those gains; throws (changing nothing) when
  // they overflow. A change of integrator or dt while it holds sets its gains again.
  void grab(int particle, const Eigen::Vector2d& target, const particles::MouseJointSettings& joint);
  void moveGrab(const Eigen::Vector2d& target);
  void release();
  const particles::MouseSpringForce* mouseSpring() const { return spring_; }
  // The grabbed particle's mean position over the frames it has been held,
  // at most the last grabTrailFrames (one second at 1x speed), and how many.
  static constexpr std::size_t grabTrailFrames = 60;
  Eigen::Vector2d grabbedMean() const;
  std::size_t grabbedFrames() const { return grabTrail_.size(); }
  void setPinned(int particle, bool pinned);
  void placePinned(int particle, const Eigen::Vector2d& position);  // drags a pinned particle

  // --- wind and tearing (particles/forces/wind.h, particles/tearing.h) -------
  // The edges the scene's wind pushes on (Scene::windEdges, or those of a
  // scene file's wind); none: the scene takes no wind.
  bool takesWind() const { return !scene_.windEdges.empty(); }
  // The wind that blows, or null.
  const particles::WindForce* wind() const { return wind_; }
  // Blows the wind with these settings on the scene's wind edges that are not
  // torn (or changes the settings of the wind that blows); stops it with
  // nullopt. Throws naming a bad setting, or when the scene takes no wind.
  void setWind(const std::optional<particles::WindSettings>& settings);
  // Springs stretched beyond this strain tear (0: none); throws when < 0.
  void setTearStrain(double strain);
  // One flag per scene face: none of its sides has torn (the renderer draws only these).
  const std::vector<char>& intactFaces() const;

  // --- divergence and rewind ------------------------------------------------
  std::optional<double> divergedAt() const { return divergedAt_; }
  // Why the integrator refused to step this system (e.g. implicit-euler on a
  // force without Jacobians); the pane stops until another integrator is chosen.
  const std::optional<std::string>& refusal() const { return refusal_; }
  bool stopped() const { return divergedAt_ || refusal_; }
  // The simulated time it stopped at if diverged, else its clock.
  double timeReached() const { return divergedAt_ ? *divergedAt_ : system().time(); }
  // Frames advanced since the start (the clock every pane shares; a stopped
  // pane's stays at the frame it stopped on).
  long long frames() const { return frames_; }
  long long framesWaited() const { return framesWaited_; }  // frames it owed a step and took none
  double owedTime() const { return owedTime_; }  // simulated time not yet stepped: t + owed is the shared clock
  // Drawing between steps. While frames of `frameTime` simulated seconds
  // come faster than steps (dt longer than a frame, running), the drawing
  // is the positions before the last step moved toward the state by this
  // fraction, the time owed over dt: motion stays smooth, one step behind
  // the clock. 1 (the state itself) otherwise.
  double drawnFraction(double frameTime) const;
  const Eigen::VectorXd& previousPositions() const { return previousX_; }
  const RewindBuffer& history() const { return history_; }
  // Restores the state recorded at `frame` (see history()), clears the
  // divergence and the plots. False when that frame is not recorded.
  bool rewindTo(long long frame);
  // Copies the dynamic state, pins, clock and history of another simulation
  // of the same scene, so a new compare pane starts exactly where it is.
  void copyStateFrom(const Simulation& other);

  // --- reading ------------------------------------------------------------
  const scenes::Scene& scene() const { return scene_; }
  particles::ParticleSystem& system() { return *scene_.system; }
  const particles::ParticleSystem& system() const { return *scene_.system; }
  const FrameStats& lastFrame() const { return lastFrame_; }
  // The signed area of each of the scene's faces at t = 0, for shading.
  const std::vector<double>& restFaceAreas() const { return restFaceAreas_; }
  // The mouse spring's potential ½ k |x − t|², which totalEnergy() includes,
  // and the scene's own energy without it.
  double mouseSpringEnergy() const;
  double sceneEnergy() const { return system().totalEnergy() - mouseSpringEnergy(); }
  const Trace& trace() const { return trace_; }
  long long steps() const { return steps_; }
  // Why the pane diverged (empty reason while it runs).
  const particles::Divergence& divergence() const { return divergence_; }
  // A message for the top bar, once, empty otherwise: its CG passed the
  // solver's work bound and was solved directly (particles::directFallbackMessage).
  std::string takeNotice() { return std::exchange(notice_, {}); }

 private:
  void stepAndWatch();
  void retuneGrab();  // the held joint's gains again, for a new integrator or dt

  scenes::Scene scene_;
  StepMode frameMode_ = StepMode::FixedTime;
  bool lockstepOwed_ = false;  // lockstep: this frame's step not yet taken
  std::unique_ptr<particles::Integrator> integrator_;
  int integratorIndex_;
  double dt_;
  double owedTime_ = 0.0;  // simulated time accumulated but not yet stepped
  Eigen::VectorXd previousX_;  // the positions before the last step, when dt > frameTime_ (else empty)
  double frameTime_ = 0.0;     // the last frame's simulated time (beginFrame)
  long long steps_ = 0;
  long long frames_ = 0;
  long long framesWaited_ = 0;
  bool noticedFallback_ = false;
  std::string notice_;
  particles::MouseSpringForce* spring_ = nullptr;  // owned by the system
  particles::MouseJointSettings joint_;            // the settings spring_ was made with
  std::deque<Eigen::Vector2d> grabTrail_;          // the grabbed particle at each frame's end
  particles::WindForce* wind_ = nullptr;           // owned by the system
  mutable std::vector<char> intactFaces_;
  mutable std::size_t facesCheckedAtBreaks_ = 0;   // broken links when intactFaces_ was made
  particles::DivergenceLimits limits_;
  std::vector<double> restFaceAreas_;
  particles::Divergence divergence_;
  std::optional<double> divergedAt_;
  std::optional<std::string> refusal_;
  particles::IntegratorSettings integratorSettings_;
  RewindBuffer history_;
  FrameStats lastFrame_;
  Trace trace_;
};

}  // namespace demo
