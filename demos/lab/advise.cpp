#include "lab/advise.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>

#include "lab/lab_scene.h"
#include "particles/check.h"

namespace lab {

namespace {

bool cancelled(const SurveySettings& s) { return interrupted() || (s.cancel && s.cancel->load()); }

void validate(const SurveySettings& s) {
  particles::requirePositive("horizon", s.horizon);
  particles::requirePositive("error", s.targetError);
  particles::requirePositive("abort error", s.abortError);
  if (!(s.energyBudget > 0.0) || !(s.driftBudget > 0.0))
    throw std::invalid_argument("the energy and drift budgets must be > 0 (infinite: none)");
  if (s.dtMax != 0.0) particles::requirePositive("dt max", s.dtMax);
  if (s.interval != 0.0) particles::requirePositive("interval", s.interval);
  particles::requirePositive("adaptive interval", s.adaptiveInterval);
  // Below 1e-13 the reference integration runs for minutes (rounding, not the
  // tolerance, bounds its error there), as --tolerance refuses for dopri5.
  particles::requireInRange("reference tolerance", s.referenceTolerance, kMinReferenceTolerance, 1.0);
  particles::requireInRange("safe fraction", s.safeFraction, 1e-3, 1.0);
  particles::requirePositive("grid resolution", s.gridResolution);
  if (s.members < 1) throw std::invalid_argument("members must be >= 1, got " + std::to_string(s.members));
  if (s.maxSteps < 1) throw std::invalid_argument("max steps must be >= 1, got " + std::to_string(s.maxSteps));
  if (s.repeats < 1) throw std::invalid_argument("repeats must be >= 1, got " + std::to_string(s.repeats));
  if (s.failureBound != 0.0) particles::requireInRange("failure bound", s.failureBound, 1e-6, 0.5);
  if (s.referenceMaxSteps < 0)
    throw std::invalid_argument("reference max steps must be >= 0, got " + std::to_string(s.referenceMaxSteps));
  for (const auto& name : s.integrators) particles::requireIntegrator(name);  // rejects unknown names
}

struct Measurer {
  const std::function<scenes::Scene()>& build;
  const SurveySettings& settings;
  const Trajectory& reference;
  double energyScale;

  Candidate run(const std::string& name, double dt, double tolerance, bool abortOnError) const {
    return measureRun(build, reference, name, dt, tolerance, settings.horizon, settings.failure, energyScale,
                      abortOnError ? settings.abortError : std::numeric_limits<double>::infinity(), settings.cancel);
  }
  // The same from ensemble member `member` (perturbStart), measured against the reference of
  // the start as built: its error includes the start's own offset (1e-6 of the scene's size).
  Candidate runFrom(int member, const std::string& name, double dt, double tolerance) const {
    const auto perturbed = [&] {
      scenes::Scene scene = build();
      perturbStart(scene, member);
      return scene;
    };
    return measureRun(perturbed, reference, name, dt, tolerance, settings.horizon, settings.failure, energyScale,
                      settings.abortError, settings.cancel);
  }
};

// Fixed-step schemes: dt descends the lab's grid (scan.h) from dtMax. At each
// dt the unperturbed start is measured against the reference; while the safe
// boundary is being established (nothing failed yet, or fewer than
// survivorsBelowFailure grid points survived below the lowest failure) runs
// are complete and, where it survives, the ensemble's other members run too,
// so the boundary is the lab's (boundaryOf over every member). Below
// safeFraction × the established boundary a run stops once its error exceeds
// abortError (it could meet no budget), and the ensemble is not rerun; a
// failure there still counts. The scan ends at the first point there that
// survives within targetError.
void scanSteps(const Measurer& m, const SurveySettings& s, IntegratorSurvey& out,
               const std::function<void(double)>& progress) {
  const double dtMax = s.dtMax > 0.0 ? s.dtMax : std::min(s.horizon / 20.0, 0.5);
  const double dtMin = s.horizon / static_cast<double>(s.maxSteps);
  const std::vector<double> grid = stepGridDividing(s.horizon, std::min(dtMin, dtMax), dtMax, s.gridResolution);
  std::vector<ScanRun> runs;  // complete runs at each boundary dt, every member that was run
  Boundary boundary;
  int supporting = 0;
  const auto update = [&] {
    std::vector<ScanRun> ascending = runs;
    std::stable_sort(ascending.begin(), ascending.end(), [](const ScanRun& a, const ScanRun& b) { return a.dt < b.dt; });
    const std::vector<GridSurvival> survival = survivalAt(ascending, s.horizon, s.members);
    boundary = boundaryOf(survival);
    supporting = survivorsBelowFirstFailure(survival);
  };
  const auto established = [&] { return boundary.aboveGrid() || supporting >= s.survivorsBelowFailure; };
  const auto belowSafe = [&](double dt) {
    return boundary.safeDt > 0.0 && dt <= s.safeFraction * boundary.safeDt * (1 + 1e-12);
  };
  for (std::size_t j = 0; j < grid.size() && !cancelled(s); ++j) {
    const double dt = grid[grid.size() - 1 - j];
    const bool abortable = established() && belowSafe(dt);
    Candidate c = m.run(out.integrator, dt, 0.0, abortable);
    if (cancelled(s)) break;
    out.scanned.push_back(c);
    if (progress) progress(static_cast<double>(j + 1) / grid.size());
    if (!c.aborted && (!abortable || !c.survived)) {
      runs.push_back({dt, 0, c.probe});
      // A dt one member fails fails; the others only run where it survived.
      bool survived = c.survived;
      for (int member = 1; member < s.members && survived && !abortable; ++member) {
        const std::optional<Probe> probe =
            runMember(m.build, out.integrator, dt, member, s.horizon, s.failure, s.cancel);
        if (!probe) break;  // cancelled: the scan ends below
        ++out.ensembleRuns;
        runs.push_back({dt, member, *probe});
        survived = probe->survives(s.horizon, dt);
      }
      update();
    }
    if (established() && belowSafe(dt) && withinBudgets(c, s.targetError, s)) break;
  }
  update();
  out.safeDt = boundary.safeDt;
  out.firstFailureDt = boundary.firstFailureDt;
  out.safeAtTop = boundary.aboveGrid() && boundary.safeDt > 0.0;
}

// The tolerances an adaptive scheme is scanned at, loosest first: the settings', else 1e-2 … 1e-12 by √10.
std::vector<double> toleranceLadder(const SurveySettings& s) {
  std::vector<double> tolerances = s.tolerances;
  if (tolerances.empty())
    for (int k = 0; k <= 20; ++k) tolerances.push_back(1e-2 * std::pow(10.0, -0.5 * k));
  std::sort(tolerances.rbegin(), tolerances.rend());
  return tolerances;
}

// Adaptive schemes: the tolerance descends at a fixed call interval.
void scanTolerances(const Measurer& m, const SurveySettings& s, double interval, IntegratorSurvey& out,
                    const std::function<void(double)>& progress) {
  const std::vector<double> tolerances = toleranceLadder(s);
  for (std::size_t j = 0; j < tolerances.size() && !cancelled(s); ++j) {
    Candidate c = m.run(out.integrator, interval, tolerances[j], true);
    if (cancelled(s)) break;
    out.scanned.push_back(c);
    if (progress) progress(static_cast<double>(j + 1) / tolerances.size());
    if (withinBudgets(c, s.targetError, s)) break;
  }
  out.safeDt = interval;
}

}  // namespace

Candidate measureRun(const std::function<scenes::Scene()>& build, const Trajectory& reference,
                     const std::string& integrator, double dt, double tolerance, double horizon,
                     const FailureCriterion& failure, double energyScale, double abortError,
                     const std::atomic<bool>* cancel) {
  const auto stop = [&] { return interrupted() || (cancel && cancel->load()); };
  Candidate c;
  c.integrator = integrator, c.dt = dt, c.tolerance = tolerance;
  scenes::Scene scene = build();
  particles::IntegratorSettings integratorSettings;
  if (tolerance > 0.0) integratorSettings.dopri5.tolerance = tolerance;
  auto stepper = particles::makeIntegrator(integrator, integratorSettings);
  double error = 0.0;
  long k = 0;
  const RunResult r = simulate(scene, *stepper, dt, horizon, failure, [&](const particles::ParticleSystem& system) {
    ++k;
    // round(T / dt) steps can end past T by up to dt/2 when dt does not divide T (a margin's
    // grid): the error is measured over [0, T], where the reference is.
    if (k * dt > reference.duration() * (1.0 + 1e-12)) return !stop();
    error = maxParticleDistance(system.positions(), reference.positionsAt(k * dt));
    c.maxError = std::max(c.maxError, error);
    // Energy is compared where the reference has a sample.
    const double sample = k * dt / reference.interval;
    const auto nearest = static_cast<std::size_t>(std::lround(sample));
    if (std::abs(sample - nearest) < 1e-9 && nearest < reference.energy.size())
      c.energyError = std::max(c.energyError, std::abs(system.totalEnergy() - reference.energy[nearest]) / energyScale);
    c.constraintDrift = std::max(c.constraintDrift, system.maxRelativeConstraintError());
    if (c.maxError > abortError) c.aborted = true;
    return !c.aborted && !stop();
  });
  c.failure = r.reason;
  c.survived = !r.failed && !r.stopped && !r.cutShort && !stop();
  c.probe.failed = r.failed;
  c.probe.failure = r.failure;
  c.probe.time = r.time;
  c.probe.maxRelativeStretch = r.maxRelativeStretch;
  c.probe.maxEnergyRise = r.maxEnergyRise;
  if (r.failed) c.maxError = std::numeric_limits<double>::infinity();
  c.errorAtT = c.survived ? error : std::numeric_limits<double>::infinity();
  c.seconds = r.seconds;
  return c;
}

Reference makeReference(const std::function<scenes::Scene()>& build, double horizon, double interval,
                        double tolerance, const ClosedForm& closedForm, const std::atomic<bool>* cancel,
                        bool stopAtContact) {
  ReferenceSettings tight;
  tight.tolerance = tolerance;
  tight.interval = interval;
  tight.cancel = cancel;
  tight.stopAtContact = stopAtContact && !closedForm;
  // The check integrates again at 100× the tolerance, observed only about once
  // a second so that odeint chooses its own steps (observed every interval,
  // both runs would be held to the same short steps and agree trivially).
  ReferenceSettings check = tight;
  check.tolerance = 100.0 * tight.tolerance;
  check.stopAtContact = false;
  const long stride = std::max(1L, std::lround(1.0 / interval));
  check.interval = stride * interval;
  Reference out;
  scenes::Scene scene = build();
  out.trajectory = closedForm ? closedForm(horizon, interval) : odeintReference(scene, horizon, tight);
  if (tight.stopAtContact && out.trajectory.touchedWall) {
    out.description = "odeint RKF78 at tolerance " + general(tight.tolerance) + ", up to its first contact";
    return out;  // wrong past the contact: not worth checking
  }
  scenes::Scene again = build();
  const Trajectory checked = odeintReference(again, horizon, check);
  for (std::size_t k = 0; k < checked.x.size() && k * stride < out.trajectory.x.size(); ++k) {
    const double distance = maxParticleDistance(out.trajectory.x[k * stride], checked.x[k]);
    out.agreement = std::max(out.agreement, distance);
    out.partingTimes.push_back(static_cast<double>(k * stride) * interval);
    out.parting.push_back(distance);
  }
  out.description = closedForm ? "closed form (odeint RKF78 at tolerance " + general(check.tolerance) +
                                     " agrees within " + general(out.agreement) + ")"
                               : "odeint RKF78 at tolerance " + general(tight.tolerance) + " (at " +
                                     general(check.tolerance) + " it differs by " + general(out.agreement) + ")";
  return out;
}

namespace {

// One integrator's scan: its tolerances (adaptive) or its dt grid. An
// integrator may refuse a scene it has no form for (implicit Euler and a
// force without Jacobians): it is listed with its reason, never picked.
IntegratorSurvey surveyIntegrator(const Measurer& measurer, const SurveySettings& s, const std::string& name,
                                  const std::function<void(double)>& progress) {
  IntegratorSurvey out;
  out.integrator = name;
  out.adaptive = particles::requireIntegrator(name).usesTolerance;
  try {
    if (out.adaptive)
      scanTolerances(measurer, s, s.horizon / std::max(1L, std::lround(s.horizon / s.adaptiveInterval)), out,
                     progress);
    else
      scanSteps(measurer, s, out, progress);
  } catch (const std::invalid_argument& e) {
    out.refused = e.what();
    out.scanned.clear();
    out.safeDt = out.firstFailureDt = 0.0;
    out.safeAtTop = false;
  }
  return out;
}

}  // namespace

double predictableUntil(const Reference& reference, double threshold, double horizon) {
  for (std::size_t k = 0; k < reference.parting.size(); ++k)
    if (!(reference.parting[k] <= threshold)) return k > 0 ? reference.partingTimes[k - 1] : 0.0;
  return horizon;
}

namespace {

// Why the reference cannot certify an error of `budget` over the horizon
// (Survey::limit), and the longest horizon it can; empty when it can.
void limitOfReference(const Reference& reference, double budget, double horizon, Survey& survey) {
  const double threshold = budget / 10.0;
  if (reference.agreement > threshold) {
    survey.certifiableHorizon = predictableUntil(reference, threshold, horizon);
    survey.limit = "the two references (at two tolerances) part by " + general(reference.agreement) +
                   ", more than E/10 = " + general(threshold) + ", after t = " + general(survey.certifiableHorizon, 4) +
                   " s (their last common sample within it): past that time the scene is not predictable at this error (chaos, or a reference that "
                   "cannot converge), so no integrator can be certified over T";
  }
}

// A scene whose odeint reference met a contact: the reference is the self-converged run of a
// contact-aware scheme (self_convergence.h) at E/10, or the survey's limit says why there is none.
void contactReference(const std::function<scenes::Scene()>& build, const SurveySettings& s, double interval,
                      Reference& reference, Survey& survey) {
  const Trajectory& odeint = reference.trajectory;
  survey.touchedWall = true;
  survey.contact = odeint.contact + " at t = " + general(odeint.contactTime, 4) + " s";
  // The last sample before the contact: how far odeint alone holds.
  const double beforeContact = std::max(0.0, odeint.contactTime - odeint.interval);
  if (!s.contactReference) {
    survey.certifiableHorizon = beforeContact;
    survey.limit = "the odeint reference meets a contact (" + survey.contact +
                   ") and contact references are off, so no integrator can be certified past that time";
    return;
  }
  SelfConvergenceSettings settings;
  settings.interval = interval;
  settings.threshold = s.targetError / 10.0;
  settings.maxSteps = s.referenceMaxSteps > 0 ? s.referenceMaxSteps : 16 * s.maxSteps;
  settings.maxBytes = kMaxReferenceBytes;
  settings.failure = s.failure;
  settings.cancel = s.cancel;
  SelfConvergence converged = selfConvergedReference(build, s.horizon, settings);
  if (!converged.converged) {
    survey.certifiableHorizon = std::max(beforeContact, converged.agreesUntil);
    survey.limit = "the odeint reference meets a contact (" + survey.contact +
                   ") and self-convergence of the contact-aware schemes was not reached within E/10 = " +
                   general(settings.threshold) + " (" + converged.why + "), so no integrator can be certified over T";
    survey.contactReference = std::move(converged);
    return;
  }
  reference.trajectory = std::move(converged.trajectory);
  converged.trajectory = Trajectory{};
  reference.agreement = converged.difference;
  reference.description = "self-convergence of " + converged.description();
  survey.contactReference = std::move(converged);
}

}  // namespace

Survey surveyScene(const std::function<scenes::Scene()>& build, const SurveySettings& settings,
                   const ClosedForm& closedForm) {
  validate(settings);
  SurveySettings s = settings;
  s.abortError = std::max(s.abortError, s.targetError);
  scenes::Scene first = build();
  const double interval = s.interval > 0.0 ? s.interval : first.dt;
  if (interval > s.horizon)
    throw std::invalid_argument("horizon must be >= the sample interval " + general(interval) + ", got " +
                                general(s.horizon));
  // The reference holds every sample of every particle: refuse a horizon whose
  // trajectory would not fit the limit (1e300 s would throw length_error).
  const double samples = s.horizon / interval;
  const double bytes = referenceBytes(samples, first.system->size());
  if (!(bytes <= kMaxReferenceBytes))
    throw std::invalid_argument("horizon " + general(s.horizon) + " s needs a reference of " + general(samples) +
                                " samples (T / interval " + general(interval) + " s) of " +
                                std::to_string(first.system->size()) + (first.system->size() == 1 ? " particle" : " particles") +
                                ", about " + general(bytes / 1e9, 4) + " GB, more than the limit of " +
                                general(kMaxReferenceBytes / 1e9) + " GB");
  Survey survey;
  survey.scene = first.name;
  survey.horizon = s.horizon;
  survey.particles = first.system->size();
  if (s.progress) s.progress(0.0);  // valid: the reference starts
  const double scale = releasableEnergy(*first.system);

  Reference reference =
      makeReference(build, s.horizon, interval, s.referenceTolerance, closedForm, s.cancel, /*stopAtContact=*/true);
  survey.size = reference.trajectory.size();  // of the run up to any contact: relative budgets need it first
  survey.energyScale = scale;
  if (s.relativeToSize) s.abortError *= survey.size, s.targetError *= survey.size;
  if (reference.trajectory.touchedWall) {
    contactReference(build, s, interval, reference, survey);
    if (!survey.limit.empty()) {
      survey.reference = reference.description;
      return survey;
    }
    // The whole motion's size, where no budget was taken of the size up to the contact.
    if (!s.relativeToSize) survey.size = reference.trajectory.size();
  }
  survey.referenceAgreement = reference.agreement;
  survey.reference = reference.description;
  limitOfReference(reference, s.targetError, s.horizon, survey);
  if (!survey.limit.empty()) return survey;
  survey.referenceTrajectory = std::make_shared<const Trajectory>(std::move(reference.trajectory));

  std::vector<std::string> names;
  for (const auto& info : particles::integratorTable())
    if (s.integrators.empty() || std::count(s.integrators.begin(), s.integrators.end(), info.name))
      names.push_back(info.name);
  const Measurer measurer{build, s, *survey.referenceTrajectory, scale};
  for (std::size_t i = 0; i < names.size() && !cancelled(s); ++i) {
    auto progress = [&](double f) {
      if (s.progress) s.progress((i + f) / names.size());
    };
    survey.integrators.push_back(surveyIntegrator(measurer, s, names[i], progress));
  }
  return survey;
}

namespace {

// The largest scanned candidate within the budget: fixed-step ones at most safeFraction × the safe boundary.
Pick firstPick(const IntegratorSurvey& scan, const SurveySettings& s, double error) {
  Pick pick;
  for (const auto& c : scan.scanned) {
    const bool safe = scan.adaptive || c.dt <= s.safeFraction * scan.safeDt * (1 + 1e-12);
    if (!safe || !withinBudgets(c, error, s)) continue;
    const bool better = !pick.found || (scan.adaptive ? c.tolerance > pick.candidate.tolerance
                                                      : c.dt > pick.candidate.dt);
    if (better) pick.found = true, pick.candidate = c;
  }
  return pick;
}

// One grid point of a margin: whether every start survived T within the budgets, the runs
// made there (a point stops at its first failing start), and their largest max error.
struct PointCheck {
  bool passed = false;
  FailureCount runs;
  double worstError = 0.0;
};

// A pick's certification: grid points of its margin, each checked once on `starts` starts.
struct Certifier {
  const Measurer& measurer;
  const SurveySettings& s;
  double error;
  int starts;
  std::map<double, PointCheck> known;  // grid point → its check
  long runs = 0;

  // Every start at one grid point (dt, or the tolerance of an adaptive pick), measured against
  // the reference; a run that fails or misses a budget fails the point.
  const PointCheck& check(const Candidate& pick, double value) {
    const auto found = known.find(value);
    if (found != known.end()) return found->second;
    const bool adaptive = pick.tolerance > 0.0;
    PointCheck point;
    point.passed = true;
    for (int member = 0; member < starts && point.passed && !cancelled(s); ++member) {
      const Candidate c =
          measurer.runFrom(member, pick.integrator, adaptive ? pick.dt : value, adaptive ? value : 0.0);
      ++runs, ++point.runs.runs;
      point.worstError = std::max(point.worstError, c.maxError);
      if (!withinBudgets(c, error, s)) point.passed = false, ++point.runs.failures;
    }
    point.passed = point.passed && !cancelled(s);
    return known[value] = point;
  }
};

// The grid point below `failed`: the pick whose window top, value / safeFraction, lies under it.
double belowFailure(double failed, double anchor, const SurveySettings& s) {
  const std::vector<double> grid =
      stepGrid(failed * s.safeFraction * 0.5, failed * s.safeFraction / (1.0 + 1e-9), s.certifyResolution, anchor);
  return grid.empty() ? 0.0 : grid.back();
}

// The starts per grid point of a margin of `points` points: certifyMembers, or enough for the
// margin's runs to reach the failure bound asked for.
int startsFor(const SurveySettings& s, std::size_t points) {
  if (!(s.failureBound > 0.0) || points == 0) return s.certifyMembers;
  const long needed = runsForBound(s.failureBound);
  return std::max(s.certifyMembers, static_cast<int>((needed + points - 1) / static_cast<long>(points)));
}

// The margin of a pick of value v (its dt, or its tolerance): the grid certifyResolution apart,
// anchored at the first pick, over [safeFraction × v, v / safeFraction].
std::vector<double> marginOf(double v, double anchor, const SurveySettings& s) {
  return stepGrid(v * s.safeFraction, v / s.safeFraction, s.certifyResolution, anchor);
}

// Certifies a pick: every grid point of its margin passes on every start
// (Certifier::check: survives T within E and the other budgets), so that the
// margin keeps the error within E as well as the run alive. A failure moves
// the pick down to the grid point whose margin lies below it; a moved pick is
// measured again, and one that fails or misses the budget counts as a failure
// there. Ends uncertified below the survey's smallest dt (T / maxSteps) or tolerance.
void certifyPick(Certifier& certifier, Pick& pick) {
  const SurveySettings& s = certifier.s;
  const bool adaptive = pick.candidate.tolerance > 0.0;
  const auto value = [&](const Candidate& c) { return adaptive ? c.tolerance : c.dt; };
  const double anchor = value(pick.candidate);
  const double floor = adaptive ? toleranceLadder(s).back() : s.horizon / static_cast<double>(s.maxSteps);
  double failed = 0.0;  // the lowest failure so far
  while (!cancelled(s)) {
    if (failed > 0.0) {
      const double next = belowFailure(failed, anchor, s);
      if (next < floor * (1 - 1e-12)) break;
      const Candidate moved = certifier.measurer.run(pick.candidate.integrator, adaptive ? pick.candidate.dt : next,
                                                     adaptive ? next : 0.0, true);
      ++certifier.runs;
      if (!withinBudgets(moved, certifier.error, s)) {
        failed = next;
        continue;
      }
      pick.candidate = moved;
    }
    const double v = value(pick.candidate);
    const std::vector<double> margin = marginOf(v, anchor, s);
    failed = 0.0;
    for (auto point = margin.rbegin(); point != margin.rend() && failed == 0.0 && !cancelled(s); ++point)
      if (!certifier.check(pick.candidate, *point).passed) failed = *point;
    if (failed == 0.0 && !cancelled(s)) {
      pick.certifiedLo = margin.front(), pick.certifiedHi = margin.back();
      pick.starts = certifier.starts;
      pick.marginRuns = {};
      pick.marginError = 0.0;
      for (double point : margin) {
        const PointCheck& checked = certifier.known.at(point);
        pick.marginRuns += checked.runs;
        pick.marginError = std::max(pick.marginError, checked.worstError);
      }
      pick.worstError = certifier.known.at(v).worstError;
      return;
    }
  }
  if (cancelled(s)) return;
  pick.found = false;
  pick.uncertified = std::string("every ") + (adaptive ? "tolerance" : "dt") + " from the pick down to " +
                     output::formatNumber(floor) + " has a failure or an error above the budget within its margin " +
                     "(the lowest at " + output::formatNumber(failed) + ")";
}

// `repeats` timed runs of every found pick, interleaved (pick 1, 2, ..., 1, 2, ...) so that a load
// change on the machine falls on all of them alike; the median and range of each.
void timePicks(const std::function<scenes::Scene()>& build, double horizon, const SurveySettings& s,
               std::vector<Pick>& picks) {
  std::function<bool(const particles::ParticleSystem&)> carryOn;  // a cancellable run checks every step
  if (s.cancel) carryOn = [&](const particles::ParticleSystem&) { return !s.cancel->load(); };
  std::vector<std::vector<double>> perSecond(picks.size());
  for (int r = 0; r < s.repeats && !cancelled(s); ++r)
    for (std::size_t k = 0; k < picks.size() && !cancelled(s); ++k) {
      if (!picks[k].found) continue;
      const Candidate& c = picks[k].candidate;
      scenes::Scene scene = build();
      particles::IntegratorSettings integratorSettings;
      if (c.tolerance > 0.0) integratorSettings.dopri5.tolerance = c.tolerance;
      auto stepper = particles::makeIntegrator(c.integrator, integratorSettings);
      const RunResult run = simulate(scene, *stepper, c.dt, horizon, s.failure, carryOn);
      if (!run.stopped && !run.cutShort) perSecond[k].push_back(run.seconds / horizon);
    }
  for (std::size_t k = 0; k < picks.size(); ++k) {
    if (!picks[k].found) continue;
    if (perSecond[k].empty()) perSecond[k].push_back(picks[k].candidate.seconds / horizon);
    picks[k].cpuPerSimulatedSecond = median(perSecond[k]);
    picks[k].cpuMin = *std::min_element(perSecond[k].begin(), perSecond[k].end());
    picks[k].cpuMax = *std::max_element(perSecond[k].begin(), perSecond[k].end());
  }
}

}  // namespace

std::vector<Pick> pickPerIntegrator(const std::function<scenes::Scene()>& build, const Survey& survey,
                                    const SurveySettings& settings, double error) {
  std::vector<Pick> picks;
  SurveySettings s = settings;
  s.horizon = survey.horizon;
  s.abortError = error;  // a moved pick's run ends once it misses the budget
  for (const auto& scan : survey.integrators) picks.push_back(firstPick(scan, s, error));
  const bool certifying = s.certifyMembers > 0 && survey.referenceTrajectory;
  std::vector<bool> tried(picks.size(), false);
  // Which pick to certify next: every found one (certifyAll), else the cheapest and its ties.
  const auto next = [&]() -> int {
    if (!certifying || cancelled(s)) return -1;
    if (s.certifyAll) {
      for (std::size_t k = 0; k < picks.size(); ++k)
        if (picks[k].found && !tried[k]) return static_cast<int>(k);
      return -1;
    }
    const int best = cheapest(picks);
    if (best < 0) return -1;
    if (!tried[best]) return best;
    markTies(picks, best);
    for (std::size_t k = 0; k < picks.size(); ++k)
      if (picks[k].tie && !tried[k]) return static_cast<int>(k);
    return -1;
  };
  if (!s.certifyAll || !certifying) timePicks(build, survey.horizon, s, picks);
  for (int k = next(); k >= 0; k = next()) {
    if (settings.progress) settings.progress(0.8 * static_cast<double>(k) / picks.size());
    tried[k] = true;
    const Measurer measurer{build, s, *survey.referenceTrajectory, survey.energyScale};
    const double first = picks[k].candidate.tolerance > 0.0 ? picks[k].candidate.tolerance : picks[k].candidate.dt;
    Certifier certifier{measurer, s, error, startsFor(s, marginOf(first, first, s).size()), {}, 0};
    const Candidate before = picks[k].candidate;
    certifyPick(certifier, picks[k]);
    picks[k].certifyRuns = certifier.runs;
    const bool moved = picks[k].found && (picks[k].candidate.dt != before.dt ||
                                          picks[k].candidate.tolerance != before.tolerance);
    if (moved && !s.certifyAll) timePicks(build, survey.horizon, s, picks);  // all again, interleaved
  }
  if (s.certifyAll && certifying) timePicks(build, survey.horizon, s, picks);
  return picks;
}

Advice advise(const std::function<scenes::Scene()>& build, const SurveySettings& settings,
              const ClosedForm& closedForm) {
  Advice out;
  SurveySettings s = settings;
  const auto share = [&](double from, double width) {
    return settings.progress ? std::function<void(double)>([=, &settings](double f) { settings.progress(from + width * f); })
                             : std::function<void(double)>();
  };
  s.progress = share(0.0, 0.9);
  try {
    out.survey = surveyScene(build, s, closedForm);
  } catch (const Cancelled&) {
    return out;
  }
  if (cancelled(s)) return out;
  s.progress = share(0.9, 0.1);
  const double budget = s.relativeToSize ? s.targetError * out.survey.size : s.targetError;
  out.picks = pickPerIntegrator(build, out.survey, s, budget);
  if (cancelled(s)) return out;
  out.best = cheapest(out.picks);
  markTies(out.picks, out.best);
  out.complete = true;
  if (settings.progress) settings.progress(1.0);
  return out;
}

bool withinBudgets(const Candidate& c, double error, const SurveySettings& settings) {
  return c.survived && c.maxError <= error && c.energyError <= settings.energyBudget &&
         c.constraintDrift <= settings.driftBudget;
}

void markTies(std::vector<Pick>& picks, int best) {
  if (best < 0) return;
  for (int k = 0; k < static_cast<int>(picks.size()); ++k)
    picks[k].tie = k != best && picks[k].found && picks[k].cpuMin <= picks[best].cpuMax;
}

TimingSpread timingSpread(const std::vector<Pick>& picks, int best) {
  TimingSpread out;
  if (best < 0) return out;
  for (int k = 0; k < static_cast<int>(picks.size()); ++k) {
    const Pick& p = picks[k];
    if (k != best && !p.tie) continue;
    out.ties += k != best;
    const double spread = p.cpuMin > 0.0 ? p.cpuMax / p.cpuMin : 1.0;
    if (spread > out.spread) out.spread = spread, out.lo = p.cpuMin, out.hi = p.cpuMax;
  }
  return out;
}

int cheapest(const std::vector<Pick>& picks) {
  int best = -1;
  for (int k = 0; k < static_cast<int>(picks.size()); ++k)
    if (picks[k].found && (best < 0 || picks[k].cpuPerSimulatedSecond < picks[best].cpuPerSimulatedSecond)) best = k;
  return best;
}

// Every number with the digits that read back to the same double, so that
// the printed options rerun exactly the run that was measured.
std::string pickArguments(const Candidate& c) {
  std::string args = "--integrator " + c.integrator + " --dt " + output::formatNumber(c.dt);
  if (c.tolerance > 0.0) args += " --tolerance " + output::formatNumber(c.tolerance);
  return args;
}

}  // namespace lab
