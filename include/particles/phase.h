#pragma once
// A configuration at which forces and constraints are evaluated.
#include <Eigen/Core>
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

// World-space primitives that describe a force or constraint for drawing,
// so that the core knows nothing of OpenGL.
struct Sketch {
  struct Line { Eigen::Vector2d a, b; };
  struct Circle { Eigen::Vector2d centre; double radius; };
  std::vector<Line> lines;
  std::vector<Circle> circles;
};

}  // namespace particles
