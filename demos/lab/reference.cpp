#include "lab/reference.h"

#include "lab/lab.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <boost/numeric/odeint.hpp>

#include "scenes/oscillator.h"
#include "scenes/param_fields.h"

namespace lab {

double referenceBytes(double samples, std::size_t particles) {
  return samples * (48.0 * static_cast<double>(particles) + 104.0);
}


namespace {

// The first-order form y = (x, v), ẏ = (v, a(x, v)) that odeint integrates.
using State = std::vector<double>;

}  // namespace

std::string contactAt(const particles::ParticleSystem& system, const Eigen::VectorXd& x) {
  const Eigen::VectorXd& r = system.radii();
  const auto& colliders = system.colliders();
  for (std::size_t c = 0; c < colliders.size(); ++c) {
    const std::string collider =
        std::string("collider ") + std::to_string(c) + " (" + particles::colliderName(colliders[c].shape) + ")";
    for (int i = 0; i < system.size(); ++i)
      if (colliders[c].distance(x.segment<2>(2 * i)).distance < r[i])
        return "particle " + std::to_string(i) + " reaches " + collider;
    for (const particles::CollisionEdge& e : system.collisionEdges())
      if (colliders[c].sweep(x.segment<2>(2 * e.a), x.segment<2>(2 * e.b), 0.0, 0.0))
        return "the edge between particles " + std::to_string(e.a) + " and " + std::to_string(e.b) + " meets " +
               collider;
  }
  std::vector<int> discs;
  for (int i = 0; i < system.size(); ++i)
    if (system.collidable(i)) discs.push_back(i);
  if (discs.size() < 2 || !system.colliding()) return "";
  for (std::size_t a = 0; a < discs.size(); ++a)
    for (std::size_t b = a + 1; b < discs.size(); ++b) {
      const int i = discs[a], j = discs[b];
      if ((x.segment<2>(2 * i) - x.segment<2>(2 * j)).norm() < r[i] + r[j])
        return "the discs of particles " + std::to_string(i) + " and " + std::to_string(j) + " touch";
    }
  return "";
}

namespace {

// Thrown by the observer at the first contact when the reference stops there.
struct ContactReached {};

void recordSample(particles::ParticleSystem& system, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                  Trajectory& out) {
  Eigen::VectorXd a(x.size());
  system.acceleration(x, v, a);
  out.x.push_back(x);
  out.v.push_back(v);
  out.a.push_back(a);
  const particles::Snapshot saved = system.snapshot();
  system.setPositions(x);
  system.setVelocities(v);
  out.energy.push_back(system.totalEnergy());
  if (!out.touchedWall) {
    out.contact = contactAt(system, x);
    if (!out.contact.empty()) {
      out.touchedWall = true;
      out.contactTime = out.interval * static_cast<double>(out.x.size() - 1);
    }
  }
  system.restore(saved);
}

}  // namespace

Eigen::VectorXd Trajectory::positionsAt(double t) const {
  const int last = static_cast<int>(x.size()) - 1;
  const double s = std::clamp(t / interval, 0.0, static_cast<double>(last));
  const int k = std::min(static_cast<int>(std::floor(s)), std::max(last - 1, 0));
  if (last == 0) return x[0];
  const double u = s - k, h = interval;
  // Quintic Hermite basis on [0, 1] for values, first and second derivatives.
  const double u2 = u * u, u3 = u2 * u, u4 = u3 * u, u5 = u4 * u;
  const double h00 = 1 - 10 * u3 + 15 * u4 - 6 * u5, h01 = 1 - h00;
  const double h10 = u - 6 * u3 + 8 * u4 - 3 * u5, h11 = -4 * u3 + 7 * u4 - 3 * u5;
  const double h20 = 0.5 * (u2 - 3 * u3 + 3 * u4 - u5), h21 = 0.5 * (u3 - 2 * u4 + u5);
  return h00 * x[k] + h01 * x[k + 1] + h * (h10 * v[k] + h11 * v[k + 1]) + h * h * (h20 * a[k] + h21 * a[k + 1]);
}

double Trajectory::size() const {
  if (x.empty()) return 0.0;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& sample : x)
    for (int i = 0; i < sample.size() / 2; ++i) {
      lo = lo.cwiseMin(sample.segment<2>(2 * i));
      hi = hi.cwiseMax(sample.segment<2>(2 * i));
    }
  return (hi - lo).norm();
}

namespace {
// Mean spacing of the upward crossings of a signal's mean, each counted once
// it has been a tenth of a standard deviation below and then reaches the mean
// (times interpolated linearly between samples); 0 with fewer than two, or
// when the signal's standard deviation is below stillBelow.
double meanCrossingPeriod(const std::vector<double>& signal, double interval, double stillBelow) {
  const double n = static_cast<double>(signal.size());
  double mean = 0.0, squares = 0.0;
  for (double s : signal) mean += s / n;
  for (double s : signal) squares += (s - mean) * (s - mean) / n;
  const double band = 0.1 * std::sqrt(squares);
  if (!(band > 0.1 * stillBelow)) return 0.0;  // a coordinate that does not move
  std::vector<double> times;
  bool armed = false;
  for (std::size_t k = 1; k < signal.size(); ++k) {
    if (signal[k - 1] - mean < -band) armed = true;
    if (armed && signal[k - 1] < mean && signal[k] >= mean) {
      const double fraction = (mean - signal[k - 1]) / (signal[k] - signal[k - 1]);
      times.push_back((static_cast<double>(k - 1) + fraction) * interval);
      armed = false;
    }
  }
  return times.size() < 2 ? 0.0 : (times.back() - times.front()) / static_cast<double>(times.size() - 1);
}
}  // namespace

double Trajectory::slowestPeriod() const {
  double slowest = 0.0;
  double reach = size();  // the scene's size, or its distance from the origin when larger
  for (const auto& sample : x) reach = std::max(reach, sample.cwiseAbs().maxCoeff());
  const double still = 1e-6 * reach;
  for (int axis = 0; axis < 2; ++axis) {
    std::vector<double> centre;
    centre.reserve(x.size());
    for (const auto& sample : x) {
      double sum = 0.0;
      for (Eigen::Index i = axis; i < sample.size(); i += 2) sum += sample[i];
      centre.push_back(sum / static_cast<double>(sample.size() / 2));
    }
    slowest = std::max(slowest, meanCrossingPeriod(centre, interval, still));
  }
  return slowest;
}

Trajectory odeintReference(scenes::Scene& scene, double duration, const ReferenceSettings& settings) {
  namespace odeint = boost::numeric::odeint;
  particles::ParticleSystem& system = *scene.system;
  system.solver().settings.tolerance = settings.solverTolerance;
  const int n2 = 2 * system.size();
  Trajectory out;
  out.interval = settings.interval;
  const long samples = std::lround(duration / settings.interval);
  std::vector<double> times(samples + 1);
  for (long k = 0; k <= samples; ++k) times[k] = k * settings.interval;

  State y(2 * n2);
  Eigen::Map<Eigen::VectorXd>(y.data(), n2) = system.positions();
  Eigen::Map<Eigen::VectorXd>(y.data() + n2, n2) = system.velocities();
  Eigen::VectorXd x(n2), v(n2), a(n2);
  auto rhs = [&](const State& state, State& derivative, double) {
    x = Eigen::Map<const Eigen::VectorXd>(state.data(), n2);
    v = Eigen::Map<const Eigen::VectorXd>(state.data() + n2, n2);
    system.acceleration(x, v, a);
    Eigen::Map<Eigen::VectorXd>(derivative.data(), n2) = v;
    Eigen::Map<Eigen::VectorXd>(derivative.data() + n2, n2) = a;
  };
  auto observe = [&](const State& state, double) {
    if (settings.cancel && settings.cancel->load()) throw Cancelled();
    recordSample(system, Eigen::Map<const Eigen::VectorXd>(state.data(), n2),
                 Eigen::Map<const Eigen::VectorXd>(state.data() + n2, n2), out);
    if (settings.stopAtContact && out.touchedWall) throw ContactReached();
  };
  auto stepper = odeint::make_controlled(settings.tolerance, settings.tolerance,
                                         odeint::runge_kutta_fehlberg78<State>());
  try {
    odeint::integrate_times(stepper, rhs, y, times.begin(), times.end(), settings.interval / 10, observe);
  } catch (const ContactReached&) {
    // The trajectory ends at its first contact: what follows it would be wrong.
  }
  return out;
}

std::optional<Trajectory> steppedTrajectory(const std::function<scenes::Scene()>& build, const std::string& integrator,
                                            double dt, long stride, double duration,
                                            const FailureCriterion& criterion, const std::atomic<bool>* cancel) {
  scenes::Scene scene = build();
  // Samples are evaluated on a second copy: the stepped system is only read,
  // so that sampling leaves the run exactly as an unobserved one.
  scenes::Scene evaluator = build();
  Trajectory out;
  out.interval = stride * dt;
  recordSample(*evaluator.system, scene.system->positions(), scene.system->velocities(), out);
  auto stepper = particles::makeIntegrator(integrator);
  long k = 0;
  bool cancelled = false;
  const RunResult run = simulate(scene, *stepper, dt, duration, criterion, [&](const particles::ParticleSystem& s) {
    if (++k % stride == 0) recordSample(*evaluator.system, s.positions(), s.velocities(), out);
    cancelled = interrupted() || (cancel && cancel->load());
    return !cancelled;
  });
  if (cancelled || run.cutShort) throw Cancelled();
  if (run.failed) return std::nullopt;
  return out;
}

Trajectory oscillatorReference(const std::map<std::string, std::string>& params, double duration, double interval,
                               const std::string& preset) {
  const auto p = scenes::readParams<scenes::OscillatorParams>(
      scenes::SceneParams(scenes::paramSpecs<scenes::OscillatorParams>(), params, preset));
  scenes::Scene scene = scenes::buildScene("oscillator", params, preset);
  particles::ParticleSystem& system = *scene.system;
  Trajectory out;
  out.interval = interval;
  const long samples = std::lround(duration / interval);
  // The bob (particle 1) moves on the x axis at rest + u(t); u̇ by a central
  // difference of the closed form is only used for a, which is interpolation data.
  for (long k = 0; k <= samples; ++k) {
    const double t = k * interval, e = 1e-6;
    Eigen::VectorXd x = system.positions(), v = Eigen::VectorXd::Zero(x.size());
    x(2) = p.rest + scenes::oscillatorDisplacement(p, t);
    v(2) = (scenes::oscillatorDisplacement(p, t + e) - scenes::oscillatorDisplacement(p, t - e)) / (2 * e);
    recordSample(system, x, v, out);
  }
  return out;
}

double maxParticleDistance(const Eigen::VectorXd& x, const Eigen::VectorXd& y) {
  double worst = 0.0;
  for (int i = 0; i < x.size() / 2; ++i) {
    const double e = (x.segment<2>(2 * i) - y.segment<2>(2 * i)).norm();
    if (!std::isfinite(e)) return std::numeric_limits<double>::infinity();
    worst = std::max(worst, e);
  }
  return worst;
}

double maxTrajectoryDistance(const Trajectory& a, const Trajectory& b) {
  double worst = 0.0;
  const std::size_t n = std::min(a.x.size(), b.x.size());
  for (std::size_t k = 0; k < n; ++k) worst = std::max(worst, maxParticleDistance(a.x[k], b.x[k]));
  return worst;
}

}  // namespace lab
