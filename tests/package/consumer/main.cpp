// A project outside the tree: the installed engine through one include, with a
// force and a constraint of its own, under every integrator of the table.
//   wind:   a steady push F on a free particle of mass m from rest: x = F t²/(2m)
//   tether: a pendulum of length r held to a fixed anchor by a constraint
//           written here (C = |d| − r): |C| stays below 1e-3 r over 2 s
// Exits 0 only when every integrator meets both.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <particles/particles.h>

namespace {

class WindForce : public particles::Force {
 public:
  explicit WindForce(Eigen::Vector2d push) : push_(push) {}
  const char* type() const override { return "wind"; }
  void apply(const particles::Phase& s, Eigen::VectorXd& f) const override {
    for (int i = 0; i < s.size(); ++i) f.segment<2>(2 * i) += push_;
  }
  // A constant force: both Jacobians are zero (what an implicit scheme needs).
  bool hasJacobians() const override { return true; }
  void addJacobians(const particles::Phase&, particles::Triplets&, particles::Triplets&) const override {}

 private:
  Eigen::Vector2d push_;
};

class TetherConstraint : public particles::Constraint {
 public:
  TetherConstraint(int particle, Eigen::Vector2d anchor, double length)
      : Constraint({particle}), anchor_(anchor), length_(length) {}
  const char* type() const override { return "tether"; }
  // C = |d| − r, J = u = d/|d|, J̇ = (v − u (u·v)) / |d|, Ċ = u·v.
  void evaluate(const particles::Phase& s, particles::ConstraintRow& row) const override {
    const Eigen::Vector2d d = s.position(particles()[0]) - anchor_, v = s.velocity(particles()[0]);
    const double n = d.norm();
    const Eigen::Vector2d u = d / n;
    row.C = n - length_;
    row.Cdot = u.dot(v);
    row.J[0] = u;
    row.Jdot[0] = (v - u * u.dot(v)) / n;
  }
  double violation(const particles::Phase& s) const override {
    return std::abs((s.position(particles()[0]) - anchor_).norm() - length_);
  }
  double lengthScale() const override { return length_; }
  void sketch(const particles::Phase&, particles::Sketch&) const override {}

 private:
  Eigen::Vector2d anchor_;
  double length_;
};

double windError(const std::string& name) {
  const double m = 2.0, F = 3.0, dt = 1e-3, T = 1.0;
  particles::ParticleSystem system;
  system.addParticle({0.0, 0.0}, m);
  system.addForce(std::make_unique<WindForce>(Eigen::Vector2d(F, 0.0)));
  auto integrator = particles::makeIntegrator(name);
  for (int k = 0; k < 1000; ++k) system.step(*integrator, dt);
  const double exact = F * T * T / (2.0 * m);
  return std::abs(system.position(0).x() - exact) / exact;
}

double tetherError(const std::string& name) {
  const double r = 1.0, dt = 1e-3;
  particles::ParticleSystem system;
  system.addParticle({r * std::sin(0.5), -r * std::cos(0.5)}, 1.0);
  system.addForce(std::make_unique<particles::GravityForce>(Eigen::Vector2d(0.0, -9.81)));
  system.addForce(std::make_unique<WindForce>(Eigen::Vector2d(0.5, 0.0)));
  system.addConstraint(std::make_unique<TetherConstraint>(0, Eigen::Vector2d::Zero(), r));
  auto integrator = particles::makeIntegrator(name);
  double worst = 0.0;
  for (int k = 0; k < 2000; ++k) {
    system.step(*integrator, dt);
    worst = std::fmax(worst, system.maxConstraintError() / r);
  }
  return worst;
}

}  // namespace

int main() {
  bool ok = true;
  for (const particles::IntegratorInfo& info : particles::integratorTable()) {
    const double wind = windError(info.name), tether = tetherError(info.name);
    const bool pass = wind < 1e-2 && tether < 1e-3;
    std::printf("%-16s wind x off by %.2e of F t^2/2m, tether max |C|/r %.2e: %s\n", info.name, wind, tether,
                pass ? "ok" : "wrong");
    ok = ok && pass;
  }
  std::printf("every integrator: %s\n", ok ? "ok" : "wrong");
  return ok ? 0 : 1;
}
