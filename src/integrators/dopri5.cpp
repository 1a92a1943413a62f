#include "particles/integrators/dopri5.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "particles/particle_system.h"

namespace particles {

namespace {

// Dormand–Prince coefficients (HNW I, Table II.5.2): row s of a holds a_{s+1,j};
// b the fifth-order weights (= a₇ⱼ, so y₁ is stage 7's state); e = b − b̂.
constexpr double a[6][6] = {
    {0.0},
    {1.0 / 5.0},
    {3.0 / 40.0, 9.0 / 40.0},
    {44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0},
    {19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0},
    {9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0},
};
constexpr double b[6] = {35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0};
constexpr double e[7] = {71.0 / 57600.0,      0.0,         -71.0 / 16695.0, 71.0 / 1920.0,
                         -17253.0 / 339200.0, 22.0 / 525.0, -1.0 / 40.0};

// Dense output (HNW II.6, the continuous extension of DOPRI5 by Shampine, of
// order 4): y(t₀ + θh) = r₁ + θ (r₂ + (1−θ) (r₃ + θ (r₄ + (1−θ) r₅))) with
//   r₁ = y₀,  r₂ = y₁ − y₀,  r₃ = h k₁ − r₂,  r₄ = r₂ − h k₇ − r₃,
//   r₅ = h Σ dᵢ kᵢ  (the dᵢ below; d₂ = 0).
constexpr double d[7] = {-12715105075.0 / 11282082432.0, 0.0, 87487479700.0 / 32700410799.0,
                         -10690763975.0 / 1880347072.0,  701980252875.0 / 199316789632.0,
                         -1453857185.0 / 822651844.0,    69997945.0 / 29380423.0};

// PI controller constants (HNW II.4; DOPRI5's defaults).
constexpr double kBeta = 0.04, kAlpha = 0.2 - 0.75 * kBeta, kSafety = 0.9;
constexpr double kShrinkLimit = 0.2, kGrowLimit = 10.0;
constexpr double kRejected = 1e10;  // err of a trial that produced a non-finite state

}  // namespace

void Dopri5Integrator::configure(const IntegratorSettings& settings) {
  settings.validate();
  settings_ = settings;
}

double Dopri5Integrator::trial(ParticleSystem& system, double h) {
  for (int s = 1; s < 6; ++s) {
    xs_ = x0_;
    vs_ = v0_;
    for (int j = 0; j < s; ++j) {
      if (a[s][j] == 0.0) continue;
      xs_ += (h * a[s][j]) * kx_[j];
      vs_ += (h * a[s][j]) * kv_[j];
    }
    kx_[s] = vs_;
    system.acceleration(xs_, vs_, kv_[s]);
  }
  x1_ = x0_;
  v1_ = v0_;
  for (int j = 0; j < 6; ++j) {
    if (b[j] == 0.0) continue;
    x1_ += (h * b[j]) * kx_[j];
    v1_ += (h * b[j]) * kv_[j];
  }
  kx_[6] = v1_;
  system.acceleration(x1_, v1_, kv_[6]);

  // err = sqrt(mean((e_i / sc_i)²)) over the 2N components of (x, v).
  double sum = 0.0;
  const Eigen::Index n = x0_.size();
  for (Eigen::Index i = 0; i < n; ++i) {
    double ex = 0.0, ev = 0.0;
    for (int j = 0; j < 7; ++j) {
      if (e[j] == 0.0) continue;
      ex += e[j] * kx_[j][i];
      ev += e[j] * kv_[j][i];
    }
    const double sx = settings_.tolerance * (1.0 + std::max(std::abs(x0_[i]), std::abs(x1_[i])));
    const double sv = settings_.tolerance * (1.0 + std::max(std::abs(v0_[i]), std::abs(v1_[i])));
    sum += (h * ex / sx) * (h * ex / sx) + (h * ev / sv) * (h * ev / sv);
  }
  const double err = n > 0 ? std::sqrt(sum / (2.0 * n)) : 0.0;
  return std::isfinite(err) ? err : kRejected;
}

// HNW II.4's starting step: h₀ = 0.01 |y₀|/|f₀| (scaled norms), one explicit
// Euler probe to estimate |f'|, then h = min(100 h₀, (0.01 / max(|f₀|, |f'|))^(1/5)).
double Dopri5Integrator::initialStep(ParticleSystem& system, double dt) {
  const Eigen::Index n = x0_.size();
  auto scaledRms = [&](const Eigen::VectorXd& px, const Eigen::VectorXd& pv) {
    double sum = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double sx = settings_.tolerance * (1.0 + std::abs(x0_[i]));
      const double sv = settings_.tolerance * (1.0 + std::abs(v0_[i]));
      sum += (px[i] / sx) * (px[i] / sx) + (pv[i] / sv) * (pv[i] / sv);
    }
    return n > 0 ? std::sqrt(sum / (2.0 * n)) : 0.0;
  };
  const double d0 = scaledRms(x0_, v0_), d1 = scaledRms(kx_[0], kv_[0]);
  double h0 = d0 < 1e-5 || d1 < 1e-5 ? 1e-6 : 0.01 * d0 / d1;
  h0 = std::min(h0, dt);
  xs_ = x0_ + h0 * kx_[0];
  vs_ = v0_ + h0 * kv_[0];
  system.acceleration(xs_, vs_, a_);
  const double d2 = scaledRms(vs_ - kx_[0], a_ - kv_[0]) / h0;
  const double dMax = std::max(d1, d2);
  const double h1 = dMax <= 1e-15 ? std::max(1e-6, 1e-3 * h0) : std::pow(0.01 / dMax, 0.2);
  const double h = std::min({100.0 * h0, h1, dt});
  return std::isfinite(h) && h > 0.0 ? h : dt;
}

void Dopri5Integrator::prepareDenseOutput(double h) {
  for (auto [y0, y1, k, r] : {std::tie(x0_, x1_, kx_, denseX_), std::tie(v0_, v1_, kv_, denseV_)}) {
    r[0] = y0;
    r[1] = y1 - y0;
    r[2] = h * k[0] - r[1];
    r[3] = r[1] - h * k[6] - r[2];
    r[4] = (h * d[0]) * k[0];
    for (int j = 2; j < 7; ++j) r[4] += (h * d[j]) * k[j];
  }
  denseStep_ = h;
}

void Dopri5Integrator::denseOutput(double theta, Eigen::VectorXd& x, Eigen::VectorXd& v) const {
  const double u = 1.0 - theta;
  x = denseX_[0] + theta * (denseX_[1] + u * (denseX_[2] + theta * (denseX_[3] + u * denseX_[4])));
  v = denseV_[0] + theta * (denseV_[1] + u * (denseV_[2] + theta * (denseV_[3] + u * denseV_[4])));
}

StepStats Dopri5Integrator::step(ParticleSystem& system, double dt) {
  Eigen::VectorXd& x = system.positions();
  Eigen::VectorXd& v = system.velocities();
  // The internal solution (x0_, v0_, lead_ ahead of the output) and k₁ there
  // (FSAL: the last accepted step's k₇) carry on only while the system holds
  // exactly the state this integrator returned; anything else (a collision, a
  // drag, a restore) restarts it from the system's state.
  const bool resume = cached_ && xCached_.size() == x.size() && xCached_ == x && vCached_ == v;
  if (!resume) {
    x0_ = x;
    v0_ = v;
    lead_ = 0.0;
    kx_[0] = v0_;
    system.acceleration(x0_, v0_, kv_[0]);
  }
  StepStats stats;
  stats.internalSteps = 0;
  lastStep_ = 0.0;  // becomes the largest step accepted in this call

  if (!adaptive) {
    trial(system, dt);
    x0_.swap(x1_);
    v0_.swap(v1_);
    std::swap(kx_[0], kx_[6]);
    std::swap(kv_[0], kv_[6]);
    stats.internalSteps = 1;
    lastStep_ = dt;
    x = x0_;
    v = v0_;
  } else {
    if (!(h_ > 0.0) || !std::isfinite(h_)) h_ = initialStep(system, dt);
    const double floor = settings_.minStepFraction * dt;
    bool rejectedLast = false;
    long attempts = 0;
    // Internal steps of h_ until the internal solution reaches the output
    // time; none is cut short to land on it (within rounding it lands anyway).
    while (lead_ < dt * (1.0 - 1e-12)) {
      if (++attempts > settings_.maxStepsPerCall) {
        stats.failure = StepFailure::WorkCapReached;
        break;
      }
      const double h = h_;
      const double err = trial(system, h);
      if (err <= 1.0) {
        prepareDenseOutput(h);
        x0_.swap(x1_);
        v0_.swap(v1_);
        std::swap(kx_[0], kx_[6]);
        std::swap(kv_[0], kv_[6]);
        lead_ += h;
        ++stats.internalSteps;
        lastStep_ = std::max(lastStep_, h);
        double factor = kSafety * std::pow(std::max(err, 1e-10), -kAlpha) * std::pow(errPrevious_, kBeta);
        factor = std::clamp(factor, kShrinkLimit, rejectedLast ? 1.0 : kGrowLimit);
        h_ = h * factor;
        errPrevious_ = std::max(err, 1e-4);
        rejectedLast = false;
      } else {
        ++stats.rejectedSteps;
        h_ = h * std::max(kShrinkLimit, kSafety * std::pow(err, -kAlpha));
        rejectedLast = true;
        if (h_ < floor) {
          stats.failure = StepFailure::StepBelowFloor;
          break;
        }
      }
    }
    if (stats.failure != StepFailure::None || std::abs(lead_ - dt) <= 1e-12 * dt) {
      // On the internal grid (or stopped short by a failure: the last accepted state).
      x = x0_;
      v = v0_;
      lead_ = 0.0;
    } else {
      // The output time lies inside the last accepted step, lead_ − dt before its end.
      denseOutput(1.0 - (lead_ - dt) / denseStep_, x, v);
      lead_ -= dt;
    }
    if (stats.internalSteps == 0) lastStep_ = denseStep_;
  }
  xCached_ = x;
  vCached_ = v;
  cached_ = true;
  StepStats evaluations = system.takeEvaluationStats();
  evaluations.internalSteps = 0;
  stats += evaluations;
  return stats;
}

}  // namespace particles
