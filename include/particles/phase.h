#pragma once
// A configuration at which forces and constraints are evaluated.
#include <Eigen/Core>
#include <functional>
#include <vector>

namespace particles {

// Positions and velocities of all n particles as 2n vectors laid out
// (x0, y0, x1, y1, ...), beside the per-particle masses. Integrators evaluate
// forces at trial states, so forces and constraints read a Phase rather than
// the system's current state.
struct Phase {
  const Eigen::VectorXd& x;            // 2n positions
  const Eigen::VectorXd& v;            // 2n velocities
  const Eigen::VectorXd& mass;         // n masses
  const Eigen::VectorXd& inverseMass;  // n inverse masses; 0 for a pinned particle

  Eigen::Vector2d position(int i) const { return x.segment<2>(2 * i); }
  Eigen::Vector2d velocity(int i) const { return v.segment<2>(2 * i); }
  int size() const { return static_cast<int>(mass.size()); }
};

// A pass over the particles [begin, end) (entries [2 begin, 2 end) of a 2n
// vector), called over ranges that cover every particle, on several threads
// at once when the caller runs in parallel.
using ParticleRange = std::function<void(int begin, int end)>;
// The same pass in the k-th of a sequence of evaluations (an integrator's
// stages): particles [begin, end) of evaluation `stage`.
using StageRange = std::function<void(int stage, int begin, int end)>;
// Evaluation `stage`'s pass of then as a ParticleRange (empty when then is;
// it refers to then, which must outlive it).
inline ParticleRange stagePass(const StageRange& then, int stage) {
  if (!then) return {};
  return [&then, stage](int begin, int end) { then(stage, begin, end); };
}

// World-space primitives that describe a force or constraint for drawing,
// so that the core knows nothing of OpenGL.
struct Sketch {
  struct Line { Eigen::Vector2d a, b; };
  struct Circle { Eigen::Vector2d centre; double radius; };
  std::vector<Line> lines;
  std::vector<Circle> circles;
};

}  // namespace particles
