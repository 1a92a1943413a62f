#pragma once
// Reference trajectories independent of the integrators under test: the
// closed form where one exists, otherwise Boost.Odeint's controlled
// Runge–Kutta–Fehlberg 7(8) driving ParticleSystem::acceleration.
#include <atomic>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lab/failure.h"
#include "scene.h"

namespace lab {

// The reference holds T / interval samples, each of them the positions,
// velocities and accelerations of every particle (three Eigen vectors of 2n
// doubles, each with its handle and the allocator's header: 16 + 16n + 16
// bytes) and the energy: 48 n + 104 bytes a sample. A survey whose reference
// would take more than kMaxReferenceBytes is refused before it starts (a
// limit on samples alone let a one-particle scene reach 3.9 GB: 160 bytes a
// sample, of which 16 are the particle's position).
inline constexpr double kMaxReferenceBytes = 1e9;
double referenceBytes(double samples, std::size_t particles);

// States sampled on a uniform grid t_k = k·interval, k = 0..K. Between samples
// the positions are the quintic Hermite interpolant of (x, v, a) at both ends,
// error ≤ h⁶ max|x⁽⁶⁾| / 46080, far below any error a budget asks for.
class Trajectory {
 public:
  double interval = 0.0;                 // h, simulated seconds
  std::vector<Eigen::VectorXd> x, v, a;  // per sample, 2n each
  std::vector<double> energy;            // total energy per sample
  // A sample lies inside a collider, or two collidable particles overlap: the
  // reference ignored a contact. contactTime: the first such sample's time.
  bool touchedWall = false;
  double contactTime = 0.0;
  std::string contact;  // what touched first (contactAt), "" if nothing did

  double duration() const { return interval * (x.size() - 1); }
  // Positions at time t in [0, duration()].
  Eigen::VectorXd positionsAt(double t) const;
  // Diagonal of the bounding box of every particle over every sample: the
  // scene's size that relative error budgets are taken of.
  double size() const;
  // The period of the slowest motion: per coordinate of the particles' centre,
  // the mean spacing of its upward crossings of its mean (with a hysteresis of
  // a tenth of its standard deviation, so that a motion that has settled adds
  // no crossings); the longest over the two coordinates that move (a standard
  // deviation of at least 1e-6 of the larger of size() and the largest
  // coordinate). 0 when
  // neither crosses twice (no period within the horizon).
  double slowestPeriod() const;
};

struct ReferenceSettings {
  double tolerance = 1e-11;        // odeint absolute and relative error per step
  double solverTolerance = 1e-13;  // the constraint solve's, so it does not floor the reference
  double interval = 0.01;          // sample spacing h, simulated seconds
  bool stopAtContact = false;      // end the trajectory at its first contact (what follows it would be wrong)
  const std::atomic<bool>* cancel = nullptr;  // set to stop: odeintReference then throws Cancelled
};

// Thrown by a computation whose cancel flag was set.
struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("cancelled") {}
};

// Integrates a freshly built scene (collisions are not modelled: touchedWall
// reports whether that mattered) over [0, duration] with odeint's
// controlled runge_kutta_fehlberg78, observed at every sample (integrate_times);
// throws Cancelled at the first sample after settings.cancel was set.
Trajectory odeintReference(scenes::Scene& scene, double duration, const ReferenceSettings& settings = {});

// What puts positions x in contact, in words — "the discs of particles 12 and
// 14 touch", "particle 3 reaches collider 0 (box)", "the edge between
// particles 4 and 5 meets collider 1 (disc)" — or "" when nothing does.
std::string contactAt(const particles::ParticleSystem& system, const Eigen::VectorXd& x);

// A freshly built scene stepped by a fixed-step integrator of the engine's
// table at dt for round(duration / dt) steps, contacts included (each step
// ends with the contact pass), sampled every `stride` steps: the run a
// contact reference is made of (self_convergence.h). nullopt when the run
// fails by `criterion`; throws Cancelled when `cancel` (or an interrupt) stopped it.
std::optional<Trajectory> steppedTrajectory(const std::function<scenes::Scene()>& build, const std::string& integrator,
                                            double dt, long stride, double duration,
                                            const FailureCriterion& criterion, const std::atomic<bool>* cancel = nullptr);

// The oscillator scene's closed form (scenes::oscillatorDisplacement) on the
// same grid; a and energy from the scene's own evaluation at the exact state.
Trajectory oscillatorReference(const std::map<std::string, std::string>& params, double duration, double interval,
                               const std::string& preset = scenes::kDefaultPreset);

// Largest distance between corresponding particles of two position vectors;
// infinite if either is not finite.
double maxParticleDistance(const Eigen::VectorXd& x, const Eigen::VectorXd& y);

// Largest particle distance between two trajectories over their common samples.
double maxTrajectoryDistance(const Trajectory& a, const Trajectory& b);

}  // namespace lab
