#include "particles/grab.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Eigenvalues>

#include "particles/check.h"
#include "particles/constants.h"
#include "particles/integrator.h"
#include "particles/particle_system.h"

namespace particles {

void MouseJointSettings::validate() const {
  requirePositive("mouse joint frequency", frequency);
  requireNonNegative("mouse joint damping ratio", dampingRatio);
  requireNonNegative("mouse joint stiffness ratio", stiffnessRatio);
}

namespace {

// Union–find over particles, for the tied mass.
struct Groups {
  std::vector<int> parent;
  explicit Groups(int n) : parent(n) {
    for (int i = 0; i < n; ++i) parent[i] = i;
  }
  int find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(int a, int b) { parent[find(a)] = find(b); }
};

}  // namespace

GrabReach grabReach(const ParticleSystem& system, int particle, const Force* ignore) {
  requireIndex("grab", particle, system.size());
  const int n = system.size();
  const Eigen::VectorXd& w = system.inverseMasses();
  Groups groups(n);
  // Only movable particles join a group: a pin holds, it is not dragged along.
  const auto tie = [&](int a, int b) {
    if (a != b && w[a] > 0.0 && w[b] > 0.0) groups.join(a, b);
  };
  Triplets dfdx, dfdv;
  const Phase phase = system.phase();
  for (const auto& force : system.forceObjects())
    if (force.get() != ignore && force->hasJacobians()) force->addDefiniteJacobians(phase, dfdx, dfdv);
  Eigen::Matrix2d block = Eigen::Matrix2d::Zero();
  for (const auto& t : dfdx) {
    if (t.value() == 0.0) continue;
    const int a = static_cast<int>(t.row() / 2), b = static_cast<int>(t.col() / 2);
    tie(a, b);
    if (a == particle && b == particle) block(t.row() % 2, t.col() % 2) -= t.value();
  }
  GrabReach reach;
  for (const auto& constraint : system.constraints()) {
    const std::vector<int>& p = constraint->particles();
    for (std::size_t k = 1; k < p.size(); ++k) tie(p[0], p[k]);
    reach.constrained = reach.constrained || std::find(p.begin(), p.end(), particle) != p.end();
  }
  reach.mass = system.masses()[particle];
  const int group = groups.find(particle);
  for (int i = 0; i < n; ++i)
    if (i == particle || (w[i] > 0.0 && groups.find(i) == group)) reach.tiedMass += system.masses()[i];
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(0.5 * (block + block.transpose()),
                                                            Eigen::EigenvaluesOnly);
  reach.stiffness = std::max(0.0, eigen.eigenvalues()(1));
  return reach;
}

double explicitForceStep(const std::string& scheme, double dt) {
  const IntegratorInfo* info = findIntegrator(scheme);
  return info != nullptr && info->implicitForces ? 0.0 : dt;
}

MouseSpringGains mouseSpringGains(const GrabReach& reach, const MouseJointSettings& joint, double explicitStep) {
  requirePositive("grabbed mass", reach.mass);
  requirePositive("grabbed tied mass", reach.tiedMass);
  requireNonNegative("grabbed attached stiffness", reach.stiffness);
  requireNonNegative("explicit force step", explicitStep);
  joint.validate();
  const double omega = 2.0 * kPi * joint.frequency;
  double stiffness = std::max(reach.tiedMass * omega * omega, joint.stiffnessRatio * reach.stiffness);
  double damping = 2.0 * joint.dampingRatio * std::sqrt(stiffness * reach.tiedMass);
  if (explicitStep > 0.0) {
    const double rate = reach.constrained ? kExplicitJointRate : 1.0;
    stiffness = std::min(stiffness, rate * rate * reach.mass / (explicitStep * explicitStep));
    damping = std::min(damping, 0.5 * reach.mass / explicitStep);
  }
  if (!std::isfinite(stiffness) || !std::isfinite(damping))
    throw std::invalid_argument("mouse joint stiffness overflows for mass " + formatValue(reach.tiedMass) + " at " +
                                formatValue(joint.frequency) + " Hz");
  return {stiffness, damping};
}

}  // namespace particles
