#include "lab/self_convergence.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "lab/lab.h"
#include "lab/lab_scene.h"
#include "output/format_number.h"

namespace lab {

namespace {

// The time of the last common sample before the runs first part by more than
// `threshold` (the whole common span if they never do).
double agreementSpan(const Trajectory& a, const Trajectory& b, double threshold) {
  const std::size_t n = std::min(a.x.size(), b.x.size());
  for (std::size_t k = 0; k < n; ++k)
    if (!(maxParticleDistance(a.x[k], b.x[k]) <= threshold)) return k > 0 ? (k - 1) * a.interval : 0.0;
  return n > 0 ? (n - 1) * a.interval : 0.0;
}

// The differences of the halvings, "0.022 at dt 0.00025, 0.019 at 0.000125, ...".
std::string differencesText(const std::vector<Halving>& halvings) {
  std::string text;
  for (const Halving& h : halvings) {
    if (!std::isfinite(h.difference)) continue;
    text += (text.empty() ? "" : ", ") + output::formatGeneral(h.difference, 2) + (text.empty() ? " at dt " : " at ") +
            output::formatGeneral(h.dt, 3);
  }
  return text.empty() ? "none comparable" : text;
}

// The order fitted to the last three differences (least squares of log d
// against log dt); NaN with fewer than three in a row.
double recentOrder(const std::vector<Halving>& halvings) {
  if (halvings.size() < 3) return std::nan("");
  std::vector<double> x, y;
  for (std::size_t k = halvings.size() - 3; k < halvings.size(); ++k) {
    if (!std::isfinite(halvings[k].difference) || !(halvings[k].difference > 0.0)) return std::nan("");
    x.push_back(std::log(halvings[k].dt)), y.push_back(std::log(halvings[k].difference));
  }
  const double mx = (x[0] + x[1] + x[2]) / 3.0, my = (y[0] + y[1] + y[2]) / 3.0;
  double sxy = 0.0, sxx = 0.0;
  for (int k = 0; k < 3; ++k) sxy += (x[k] - mx) * (y[k] - my), sxx += (x[k] - mx) * (x[k] - mx);
  return sxy / sxx;
}

// The fastest any particle moves at a sample of the run.
double fastest(const Trajectory& run) {
  double speed = 0.0;
  for (const Eigen::VectorXd& v : run.v)
    for (Eigen::Index i = 0; i + 1 < v.size(); i += 2) speed = std::max(speed, std::hypot(v[i], v[i + 1]));
  return speed;
}

// The converged run as the reference: sampled every `stride` steps if no particle moves more
// than the threshold between those samples, else run again with samples that close (halving
// the interval; at most every step, and at most settings.maxBytes of samples).
void resample(const std::function<scenes::Scene()>& build, double horizon, const SelfConvergenceSettings& s,
              long stride, Trajectory& run, SelfConvergence& out) {
  const double speed = fastest(run);
  const std::size_t particles = run.x.empty() ? 1 : std::max<std::size_t>(1, run.x[0].size() / 2);
  long fine = stride;
  while (fine > 1 && fine * out.dt * speed > s.threshold &&
         referenceBytes(horizon / (0.5 * fine * out.dt), particles) <= s.maxBytes)
    fine = (fine + 1) / 2;
  if (fine < stride) {
    std::optional<Trajectory> again = steppedTrajectory(build, out.scheme, out.dt, fine, horizon, s.failure, s.cancel);
    if (again) run = std::move(*again);  // it ran before: only a cancel could end it otherwise (thrown)
  }
  out.sampleInterval = run.interval;
  out.trajectory = std::move(run);
}

// Why halving further is hopeless, or "" while it is not: at the order the
// last three differences show, they would reach the threshold only far below
// the smallest step allowed (or they do not shrink at all).
std::string hopelessWhy(const std::vector<Halving>& halvings, double threshold, double finest) {
  const double order = recentOrder(halvings);
  if (std::isnan(order)) return "";
  const Halving& last = halvings.back();
  // dt at which the differences would reach the threshold at that order.
  const double needed = order > 0.1 ? last.dt * std::pow(threshold / last.difference, 1.0 / order) : 0.0;
  if (needed >= finest / 16.0) return "";
  return "at the order its last three differences show, " + output::formatFixed(order, 2) +
         (order > 0.1 ? ", they would reach it only near dt " + output::formatGeneral(needed, 2)
                      : ", they do not shrink") +
         ", far below the smallest step allowed";
}

// Halves one scheme's step until two successive runs agree within the
// threshold. It gives up early when the differences shrink so slowly (the
// order fitted to the last three) that they would reach the threshold only
// well below the smallest step allowed: finer runs would cost much and decide nothing.
SelfConvergence halveUntilAgreed(const std::function<scenes::Scene()>& build, double horizon,
                                 const SelfConvergenceSettings& s, const std::string& scheme) {
  SelfConvergence out;
  out.scheme = scheme;
  const long coarsest = std::max(1L, std::lround(horizon / s.interval));
  const double dt0 = horizon / static_cast<double>(coarsest);
  const double finest = horizon / static_cast<double>(s.maxSteps);
  std::optional<Trajectory> previous;
  std::string hopeless;  // why halving further was not tried
  for (long stride = 1; coarsest * stride <= s.maxSteps && hopeless.empty(); stride *= 2) {
    Halving halving;
    halving.dt = dt0 / static_cast<double>(stride);
    std::optional<Trajectory> run = steppedTrajectory(build, scheme, halving.dt, stride, horizon, s.failure, s.cancel);
    halving.failed = !run;
    if (run && previous) {
      halving.difference = maxTrajectoryDistance(*previous, *run);
      out.agreesUntil = agreementSpan(*previous, *run, s.threshold);
    }
    out.halvings.push_back(halving);
    const std::size_t k = out.halvings.size() - 1;
    if (k >= 2 && std::isfinite(out.halvings[k - 1].difference) && std::isfinite(halving.difference) &&
        halving.difference > 0.0)
      out.order = std::log2(out.halvings[k - 1].difference / halving.difference);
    if (halving.difference <= s.threshold) {
      out.converged = true;
      out.dt = halving.dt;
      out.difference = halving.difference;
      resample(build, horizon, s, stride, *run, out);
      return out;
    }
    previous = std::move(run);
    hopeless = hopelessWhy(out.halvings, s.threshold, finest);
  }
  const Halving* last = out.halvings.empty() ? nullptr : &out.halvings.back();
  if (last && previous) {
    // The same run from a start moved by 1e-6 of the scene's size: chaos, or slow convergence?
    const auto moved = [&] {
      scenes::Scene scene = build();
      perturbStart(scene, 1);
      return scene;
    };
    const long stride = std::lround(previous->interval / last->dt);
    if (const auto run = steppedTrajectory(moved, scheme, last->dt, stride, horizon, s.failure, s.cancel))
      out.startSensitivity = maxTrajectoryDistance(*previous, *run);
  }
  out.why = scheme + " halved from dt " + output::formatGeneral(dt0, 3) + " to " +
            output::formatGeneral(last ? last->dt : dt0, 3) + " (T / " + std::to_string(s.maxSteps) + " = " +
            output::formatGeneral(finest, 2) + " is the smallest step allowed); successive runs part by " +
            differencesText(out.halvings) + ", not within " + output::formatGeneral(s.threshold, 2) +
            (hopeless.empty() ? "" : "; " + hopeless);
  if (std::isfinite(out.startSensitivity))
    out.why += "; at that dt a start moved by 1e-6 of the scene's size ends " +
               output::formatGeneral(out.startSensitivity, 2) + " away" +
               (out.startSensitivity > s.threshold
                    ? ", more than E/10: at this error and step the motion depends on its start (chaos, or "
                      "contacts that a tiny change sends to other steps)"
                    : ", within E/10: the runs converge too slowly in dt");
  return out;
}

}  // namespace

std::string SelfConvergence::description() const {
  std::string text = scheme + " with contacts at dt " + output::formatGeneral(dt, 3) + " (" +
                     std::to_string(halvings.size() - 1) + " halvings from " +
                     output::formatGeneral(halvings.front().dt, 3) + "; the last two runs agree within " +
                     output::formatGeneral(difference, 2);
  if (std::isfinite(order)) text += ", observed order " + output::formatFixed(order, 2);
  return text + "; sampled every " + output::formatGeneral(sampleInterval, 3) + " s)";
}

SelfConvergence selfConvergedReference(const std::function<scenes::Scene()>& build, double horizon,
                                       const SelfConvergenceSettings& s) {
  if (!(s.interval > 0.0) || !(s.threshold > 0.0) || !(horizon > 0.0))
    throw std::invalid_argument("self-convergence: interval, threshold and horizon must be > 0");
  if (s.schemes.empty()) throw std::invalid_argument("self-convergence: no scheme to run");
  SelfConvergence last;
  std::string reasons;
  for (const std::string& scheme : s.schemes) {
    SelfConvergence tried = halveUntilAgreed(build, horizon, s, scheme);
    if (tried.converged) return tried;
    reasons += (reasons.empty() ? "" : "; ") + tried.why;
    // A scheme whose runs compared but converged too slowly meets the same contacts the next
    // one would (every scheme ends its step with the same contact pass): the next is tried
    // only when no two runs of this one could be compared (they failed).
    const bool compared = std::any_of(tried.halvings.begin(), tried.halvings.end(),
                                      [](const Halving& h) { return std::isfinite(h.difference); });
    last = std::move(tried);
    if (compared) break;
  }
  last.why = reasons;
  return last;
}

}  // namespace lab
