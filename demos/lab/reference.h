#pragma once
// Reference trajectories independent of the integrators under test: the
// closed form where one exists, otherwise Boost.Odeint's controlled
// Runge–Kutta–Fehlberg 7(8) driving ParticleSystem::acceleration.
#include <atomic>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>

#include "scene.h"

namespace lab {

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
