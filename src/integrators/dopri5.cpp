#include "integrators/dopri5.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "particles/cancel.h"
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

// Dense output (HNW II.6, the continuous extension of DOPRI5, of order 4):
//   y(t₀ + θh) = r₁ + θ (r₂ + (1−θ) (r₃ + θ (r₄ + (1−θ) r₅))) with
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
  settings_ = settings.dopri5;
}

namespace {

// out = y₀ + Σ_{j<count} (h c_j) k_j in one pass over the vectors (Eigen fuses
// the sum of a fixed number of terms into one loop, with no temporaries; the
// step is folded into the coefficients, so the pass is one multiply-add per term).
void combine(const Eigen::VectorXd& y0, double h, const double* c, const std::array<Eigen::VectorXd, 7>& k,
             int count, Eigen::VectorXd& out) {
  double w[6];
  for (int j = 0; j < count; ++j) w[j] = h * c[j];
  switch (count) {
    case 1: out = y0 + w[0] * k[0]; break;
    case 2: out = y0 + w[0] * k[0] + w[1] * k[1]; break;
    case 3: out = y0 + w[0] * k[0] + w[1] * k[1] + w[2] * k[2]; break;
    case 4: out = y0 + w[0] * k[0] + w[1] * k[1] + w[2] * k[2] + w[3] * k[3]; break;
    case 5: out = y0 + w[0] * k[0] + w[1] * k[1] + w[2] * k[2] + w[3] * k[3] + w[4] * k[4]; break;
    default: out = y0 + w[0] * k[0] + w[2] * k[2] + w[3] * k[3] + w[4] * k[4] + w[5] * k[5]; break;  // b, b₂ = 0
  }
}

// Σ_i (e_i / sc_i)² over one half of y (x or v), e = h Σ eⱼ kⱼ (e₂ = 0) and
// sc_i = 1 + max(|y₀_i|, |y₁_i|), in one pass (the tolerance is applied by the caller).
double squaredScaledError(const std::array<Eigen::VectorXd, 7>& k, const Eigen::VectorXd& y0,
                          const Eigen::VectorXd& y1, double h) {
  const double w0 = h * e[0], w2 = h * e[2], w3 = h * e[3], w4 = h * e[4], w5 = h * e[5], w6 = h * e[6];
  return ((w0 * k[0] + w2 * k[2] + w3 * k[3] + w4 * k[4] + w5 * k[5] + w6 * k[6]).array() /
          (1.0 + y0.array().abs().max(y1.array().abs())))
      .square()
      .sum();
}

}  // namespace

// The velocity is x's derivative, so the velocity of stage s is kx_[s]: v₀ is
// kx_[0], the stage velocities are formed in place and y₁'s velocity is kx_[6].
double Dopri5Integrator::trial(ParticleSystem& system, double h) {
  for (int s = 1; s < 6; ++s) {
    combine(x0_, h, a[s], kx_, s, xs_);
    combine(kx_[0], h, a[s], kv_, s, kx_[s]);
    system.acceleration(xs_, kx_[s], kv_[s]);
  }
  combine(x0_, h, b, kx_, 6, x1_);
  combine(kx_[0], h, b, kv_, 6, kx_[6]);
  system.acceleration(x1_, kx_[6], kv_[6]);

  // err = sqrt(mean((e_i / sc_i)²)) over the 2N components of (x, v).
  const Eigen::Index n = x0_.size();
  if (n == 0) return 0.0;
  const double sum = squaredScaledError(kx_, x0_, x1_, h) + squaredScaledError(kv_, kx_[0], kx_[6], h);
  const double err = std::sqrt(sum / (2.0 * n)) / settings_.tolerance;
  return std::isfinite(err) ? err : kRejected;
}

// HNW II.4's starting step: h₀ = 0.01 |y₀|/|f₀| (scaled norms), one explicit
// Euler probe to estimate |f'|, then h = min(100 h₀, (0.01 / max(|f₀|, |f'|))^(1/5)).
double Dopri5Integrator::initialStep(ParticleSystem& system, double dt) {
  const Eigen::Index n = x0_.size();
  const Eigen::VectorXd& v0 = kx_[0];
  auto scaledRms = [&](const Eigen::VectorXd& px, const Eigen::VectorXd& pv) {
    double sum = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double sx = settings_.tolerance * (1.0 + std::abs(x0_[i]));
      const double sv = settings_.tolerance * (1.0 + std::abs(v0[i]));
      sum += (px[i] / sx) * (px[i] / sx) + (pv[i] / sv) * (pv[i] / sv);
    }
    return n > 0 ? std::sqrt(sum / (2.0 * n)) : 0.0;
  };
  const double d0 = scaledRms(x0_, v0), d1 = scaledRms(kx_[0], kv_[0]);
  double h0 = d0 < 1e-5 || d1 < 1e-5 ? 1e-6 : 0.01 * d0 / d1;
  h0 = std::min(h0, dt);
  xs_ = x0_ + h0 * kx_[0];
  vs_ = v0 + h0 * kv_[0];
  system.acceleration(xs_, vs_, a_);
  const double d2 = scaledRms(vs_ - kx_[0], a_ - kv_[0]) / h0;
  const double dMax = std::max(d1, d2);
  const double h1 = dMax <= 1e-15 ? std::max(1e-6, 1e-3 * h0) : std::pow(0.01 / dMax, 0.2);
  const double h = std::min({100.0 * h0, h1, dt});
  return std::isfinite(h) && h > 0.0 ? h : dt;
}

// The continuous extension above, collected per stage:
//   y(θ) = y₀ + (c₂ − c₃ + 2c₄)(y₁ − y₀) + h [(c₃ − c₄) k₁ − c₄ k₇ + c₅ Σ dᵢ kᵢ],
//   c₂ = θ, c₃ = θ(1−θ), c₄ = θ²(1−θ), c₅ = θ²(1−θ)².
// After the swaps that accept a step, y₀ is in (x1_, kx_[6]), y₁ in (x0_, kx_[0]),
// k₁ in kx_[6], kv_[6], k₇ in kx_[0], kv_[0], and k₂…k₆ in place: intact
// until the next trial.
void Dopri5Integrator::denseOutput(double theta, Eigen::VectorXd& x, Eigen::VectorXd& v) const {
  const double u = 1.0 - theta, c3 = theta * u, c4 = theta * c3, c5 = c4 * u;
  const double alpha = theta - c3 + 2.0 * c4, h = denseStep_;
  const double w1 = h * (c3 - c4 + c5 * d[0]), w7 = h * (c5 * d[6] - c4);
  const double w3 = h * c5 * d[2], w4 = h * c5 * d[3], w5 = h * c5 * d[4], w6 = h * c5 * d[5];
  x = x1_ + alpha * (x0_ - x1_) + w1 * kx_[6] + w3 * kx_[2] + w4 * kx_[3] + w5 * kx_[4] + w6 * kx_[5] + w7 * kx_[0];
  v = kx_[6] + alpha * (kx_[0] - kx_[6]) + w1 * kv_[6] + w3 * kv_[2] + w4 * kv_[3] + w5 * kv_[4] + w6 * kv_[5] + w7 * kv_[0];
}

StepStats Dopri5Integrator::step(ParticleSystem& system, double dt) {
  Eigen::VectorXd& x = positionsOf(system);
  Eigen::VectorXd& v = velocitiesOf(system);
  // The internal solution (x0_, kx_[0], lead_ ahead of the output) and k₁ there
  // (FSAL: the last accepted step's k₇) carry on only while the system holds
  // exactly the state, structure and forces this integrator returned;
  // anything else (a collision, a drag, a restore, a torn spring, a gust)
  // restarts it from the system's state.
  if (!continuation_.matches(system)) {
    x0_ = x;
    kx_[0] = v;
    lead_ = 0.0;
    system.acceleration(x0_, kx_[0], kv_[0]);
    // An event (a contact, a drag, a restore) ends the internal step where
    // the output stood. The step proposed after the last accepted one is not
    // carried across it: in uniform gravity the error estimate vanishes and
    // the controller grows h tenfold per step, so a restart at every contact
    // would soon take steps of years whose dense output at θ ≈ dt/h rounds
    // back to the old state. The restarted step is instead the last accepted
    // one, capped by the output interval.
    if (accepted_ > 0.0) h_ = std::min(accepted_, dt);
  }
  StepStats stats;
  stats.internalSteps = 0;
  lastStep_ = 0.0;  // becomes the largest step accepted in this call

  if (!settings_.adaptive) {
    trial(system, dt);
    x0_.swap(x1_);
    kx_[0].swap(kx_[6]);
    kv_[0].swap(kv_[6]);
    stats.internalSteps = 1;
    lastStep_ = dt;
    x = x0_;
    v = kx_[0];
  } else {
    if (!(h_ > 0.0) || !std::isfinite(h_)) h_ = initialStep(system, dt);
    const double floor = settings_.minStepFraction * dt;
    bool rejectedLast = false;
    long attempts = 0;
    // Internal steps of h_ until the internal solution reaches the output
    // time; none is cut short to land on it (within rounding it lands anyway).
    // Up to maxStepsPerCall attempts of seven evaluations each: the cancel
    // flag is watched before each (particles/cancel.h).
    bool cancelled = false;
    while (lead_ < dt * (1.0 - 1e-12)) {
      if (cancelRequested()) {
        cancelled = true;
        break;
      }
      if (++attempts > settings_.maxStepsPerCall) {
        stats.failure = StepFailure::WorkCapReached;
        break;
      }
      const double h = h_;
      const double err = trial(system, h);
      if (err <= 1.0) {
        x0_.swap(x1_);
        kx_[0].swap(kx_[6]);
        kv_[0].swap(kv_[6]);
        lead_ += h;
        denseStep_ = h;
        accepted_ = h;
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
    if (cancelled || stats.failure != StepFailure::None || std::abs(lead_ - dt) <= 1e-12 * dt) {
      // On the internal grid (or stopped short: the last accepted state).
      x = x0_;
      v = kx_[0];
      lead_ = 0.0;
    } else {
      // The output time lies inside the last accepted step, lead_ − dt before
      // its end; that step's stages are intact (no trial since).
      denseOutput(1.0 - (lead_ - dt) / denseStep_, x, v);
      lead_ -= dt;
    }
    if (stats.internalSteps == 0) lastStep_ = denseStep_;
  }
  continuation_.keep(system);
  system.addEvaluationStats(stats);
  return stats;
}

}  // namespace particles
