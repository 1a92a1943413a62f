#pragma once
// The advice core: for one scene and horizon, the largest step (or loosest
// tolerance) of each integrator whose maximum particle position error over
// [0, T] against an independent reference stays within a budget, inside the
// integrator's safe range, and what it costs per simulated second. Shared by
// `particle-lab advise`, the cost-of-accuracy experiment and the demo's panel.
// Only measured points are reported; nothing is extrapolated.
#include <atomic>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "lab/failure_bound.h"
#include "lab/lab.h"
#include "lab/reference.h"
#include "lab/self_convergence.h"

namespace lab {

// Bounds of the survey's inputs: a reference tolerance below this runs for
// minutes with no gain (rounding bounds the error there, as for dopri5's
// --tolerance).
inline constexpr double kMinReferenceTolerance = 1e-13;


struct SurveySettings {
  double horizon = 10.0;            // T, simulated seconds
  double abortError = 1e-2;         // a run stops once its error exceeds this (world units)
  double targetError = 1e-4;        // the scan of an integrator ends at the first safe point within this
  // Optional budgets a pick must meet besides the position error (infinite: none): the largest
  // energy error |E − E_ref| / E_s over the run (Candidate::energyError) and the largest
  // constraint drift |C|/r (Candidate::constraintDrift).
  double energyBudget = std::numeric_limits<double>::infinity();
  double driftBudget = std::numeric_limits<double>::infinity();
  bool relativeToSize = false;      // abortError and targetError are fractions of the scene's size
  std::vector<std::string> integrators;  // empty: every integrator in the engine's table
  double dtMax = 0.0;               // largest dt scanned; 0: min(T/20, 0.5)
  long maxSteps = 100000;           // smallest dt scanned is T / maxSteps
  double gridResolution = 0.1225;   // the lab's dt grid (scan.h stepGridDividing) at 6 steps per octave
  int members = ScanSettings{}.members;  // starts whose survival sets the safe boundary (the lab's ensemble)
  double safeFraction = 0.8;        // a pick's dt is at most this × the safe boundary
  int survivorsBelowFailure = 3;    // grid points that must survive below the lowest failure
  std::vector<double> tolerances;   // adaptive schemes; empty: 1e-2 … 1e-12, factor √10
  double interval = 0.0;            // reference sample spacing; 0: the scene's dt
  double adaptiveInterval = 0.1;    // an adaptive scheme's call (output) interval, simulated seconds:
                                    // long enough that its tolerance, not the call, limits its step
  int repeats = 5;                  // timed repeats of each pick, interleaved across picks; the median is reported
  // Ties whose repeats spread wider than this (largest / smallest CPU time of the cheapest or a
  // tie) are the machine's noise rather than a measured equality: advise warns (timingSpread).
  double noisySpread = 1.5;
  // Certification of each pick (certifyPick): every dt of a grid certifyResolution apart in
  // [safeFraction × dt, dt / safeFraction] (tolerances: [safeFraction × tol, tol / safeFraction])
  // survives T within the budgets on certifyMembers starts (the start as built and perturbed
  // copies, perturbStart), its error measured against the reference of the start as built.
  int certifyMembers = 10;          // 0: picks are not certified
  // When > 0: enough starts per grid point of a margin that its runs, none failing, bound the
  // per-run failure probability by this at 95% confidence (failure_bound.h); at least certifyMembers.
  double failureBound = 0.0;
  double certifyResolution = 0.01;
  bool certifyAll = false;          // every pick; else the cheapest and its ties (a pick that moves
                                    // is timed again, and the cheapest certified pick wins)
  FailureCriterion failure;         // the failure criterion (lab/failure.h)
  double referenceTolerance = 1e-11;  // odeint's, in [kMinReferenceTolerance, 1]; the check run uses 100× this
  // A scene whose odeint reference meets a contact gets a reference by self-convergence of the
  // contact-aware schemes (self_convergence.h) instead, its finest run at most this many steps
  // (0: 16 × maxSteps); false: such a scene is refused.
  bool contactReference = true;
  long referenceMaxSteps = 0;
  std::function<void(double)> progress;        // fraction done, 0..1, on the calling thread
  const std::atomic<bool>* cancel = nullptr;   // set (from any thread) to stop early
};

// One measured configuration.
struct Candidate {
  std::string integrator;
  double dt = 0.0;            // step, or the call interval of an adaptive scheme
  double tolerance = 0.0;     // adaptive schemes; 0 for fixed-step ones
  bool survived = false;      // reached T without the failure criterion firing
  bool aborted = false;       // stopped once the error exceeded abortError
  std::string failure;        // which criterion fired, if any
  double maxError = 0.0;      // max over the run's steps of the largest particle error
  double errorAtT = 0.0;
  double energyError = 0.0;   // max |E − E_ref| over the steps / E_s (releasableEnergy)
  double constraintDrift = 0.0;  // max |C|/r over the run
  double seconds = 0.0;       // wall time of the scan run's steps
  Probe probe;                // the run as the safe-boundary scan sees it (scan.h)
};
// The fields a cell's result keeps (lab/cell_json.h).
template <class Io>
void fields(Io& io, Candidate& c) {
  io("integrator", c.integrator), io("dt", c.dt), io("tolerance", c.tolerance), io("survived", c.survived);
  io("aborted", c.aborted), io("failure", c.failure), io("max_error", c.maxError), io("error_at_t", c.errorAtT);
  io("energy_error", c.energyError), io("constraint_drift", c.constraintDrift), io("seconds", c.seconds);
}

// One run of a freshly built scene against the reference, sampled at every
// step (every call of an adaptive scheme) through the reference's interpolant;
// it stops early once the error exceeds abortError (Candidate::aborted).
Candidate measureRun(const std::function<scenes::Scene()>& build, const Trajectory& reference,
                     const std::string& integrator, double dt, double tolerance, double horizon,
                     const FailureCriterion& failure, double energyScale,
                     double abortError = std::numeric_limits<double>::infinity(),
                     const std::atomic<bool>* cancel = nullptr);

struct IntegratorSurvey {
  std::string integrator;
  bool adaptive = false;
  // The safe boundary (scan.h boundaryOf) over every member of the ensemble at
  // each dt run to T while it was being established.
  double safeDt = 0.0;        // largest scanned dt below which every scanned dt survived (0: none)
  double firstFailureDt = 0.0;  // lowest failing dt scanned above safeDt (0: none failed)
  bool safeAtTop = false;     // nothing failed: safeDt is the top of the grid, a lower bound
  std::vector<Candidate> scanned;  // the unperturbed start, in scan order (dt or tolerance descending)
  long ensembleRuns = 0;           // runs of the perturbed members (survival only)
  std::string refused;             // why the integrator refuses this scene ("" if it takes it)
};

struct Survey {
  std::string scene;
  double horizon = 0.0;
  double size = 0.0;                 // diagonal of the reference's bounding box, world units
  double referenceAgreement = 0.0;   // max distance between the references at two tolerances
  std::string reference;             // how it was computed
  bool touchedWall = false;          // the odeint reference met a contact (it models none)
  std::string contact;               // what it met and when ("" if nothing): "the discs of ... touch at t = ..."
  // The contact reference, when touchedWall: the halvings of the scheme that converged (or the
  // last one tried), its step and observed order; its trajectory is referenceTrajectory.
  SelfConvergence contactReference;
  int particles = 0;
  // Why no integrator can be certified within E over T, empty if one can:
  // the references part by more than E/10 before T (chaos: the scene is not
  // predictable that long at that error), or the odeint reference meets a
  // contact and no contact-aware scheme converged to within E/10 (or contact
  // references are off). Then no integrator is scanned, and certifiableHorizon
  // is the longest T from 0 over which a reference still holds.
  std::string limit;
  double certifiableHorizon = 0.0;
  std::vector<IntegratorSurvey> integrators;
  // What the scans measured against, kept for certifying the picks (pickPerIntegrator).
  std::shared_ptr<const Trajectory> referenceTrajectory;
  double energyScale = 0.0;
};

// A closed-form reference: the trajectory over [0, duration] sampled every interval.
using ClosedForm = std::function<Trajectory(double duration, double interval)>;

// A reference with its check: `agreement` is the largest particle distance
// between it and odeint at 100× the tolerance, at common samples about 1 s apart.
struct Reference {
  Trajectory trajectory;
  double agreement = 0.0;
  std::string description;
  // The references' distance at each common sample (about 1 s apart): parting[k] at time partingTimes[k].
  std::vector<double> partingTimes, parting;
};
// The longest T from 0 over which the references agree within `threshold`:
// the last common sample before the first that parts by more (the horizon if none does).
double predictableUntil(const Reference& reference, double threshold, double horizon);
// Throws Cancelled once `cancel` is set. With stopAtContact, an odeint
// reference ends at its first contact (Trajectory::touchedWall), unchecked.
Reference makeReference(const std::function<scenes::Scene()>& build, double horizon, double interval,
                        double tolerance, const ClosedForm& closedForm = {},
                        const std::atomic<bool>* cancel = nullptr, bool stopAtContact = false);

// Runs the reference and scans every integrator. `build` makes a fresh scene
// each call. The reference is the closed form when one is given (checked
// against odeint), otherwise odeint at referenceTolerance (checked against
// odeint at 100× that). Throws std::invalid_argument for bad settings and
// Cancelled when settings.cancel is set while the reference is computed (a
// scan cancelled later returns the points measured so far).
Survey surveyScene(const std::function<scenes::Scene()>& build, const SurveySettings& settings,
                   const ClosedForm& closedForm = {});

struct Pick {
  bool found = false;
  Candidate candidate;        // the run from the start as built
  double cpuPerSimulatedSecond = 0.0, cpuMin = 0.0, cpuMax = 0.0;  // median and spread of repeats
  // The certified margin around the pick (dt, or the tolerance of an adaptive
  // scheme): every grid point in [certifiedLo, certifiedHi] survived within the
  // budgets on every start; 0 when not certified. certifyRuns: the runs it took
  // (the picks moved down past failures included).
  double certifiedLo = 0.0, certifiedHi = 0.0;
  long certifyRuns = 0;
  int starts = 0;             // starts run at each grid point of the margin
  FailureCount marginRuns;    // the margin's runs (no failure when certified): the bound they support
  double worstError = 0.0;    // largest max error over the starts at the pick's own dt (tolerance)
  double marginError = 0.0;   // largest max error over every run of the margin
  std::string uncertified;  // why no pick could be certified ("" when one was or none was tried)
  bool tie = false;         // within the timing spread of the cheapest (their repeats' ranges overlap)
  bool certified() const { return certifiedHi > 0.0; }
  // The error a user should expect of the pick: over every start when certified, else the start as built.
  double error() const { return certified() ? worstError : candidate.maxError; }
};
template <class Io>
void fields(Io& io, Pick& p) {
  io("found", p.found), io("candidate", p.candidate), io("cpu_per_simulated_second", p.cpuPerSimulatedSecond);
  io("cpu_min", p.cpuMin), io("cpu_max", p.cpuMax), io("certified_lo", p.certifiedLo);
  io("certified_hi", p.certifiedHi), io("certify_runs", p.certifyRuns), io("starts", p.starts);
  io("margin_runs", p.marginRuns), io("worst_error", p.worstError), io("margin_error", p.marginError);
  io("uncertified", p.uncertified), io("tie", p.tie);
}

// 1 − error / E: how much of the budget E a pick leaves unused.
inline double headroom(const Pick& pick, double error) { return 1.0 - pick.error() / error; }
// A pick whose error is within 5% of E has no headroom worth the name: flagged.
inline constexpr double kThinHeadroom = 0.05;
inline bool thinHeadroom(const Pick& pick, double error) { return headroom(pick, error) < kThinHeadroom; }

// Per integrator, the largest scanned safe dt (fixed-step: dt ≤ safeFraction ×
// safeDt) or loosest tolerance whose maxError ≤ error, timed over `repeats`
// interleaved across the picks; the cheapest and its ties (every pick with
// settings.certifyAll) certified (certifyPick: moved down past any failure in
// its margin, then timed again) until the cheapest is a certified pick.
std::vector<Pick> pickPerIntegrator(const std::function<scenes::Scene()>& build, const Survey& survey,
                                    const SurveySettings& settings, double error);

// Index of the cheapest found pick by median CPU time, −1 if none is found.
// A run that survived T within the position error `error` and the settings'
// energy and drift budgets: what every scan, pick and certification asks.
bool withinBudgets(const Candidate& c, double error, const SurveySettings& settings);

int cheapest(const std::vector<Pick>& picks);
// Marks the found picks whose timing range (min–max of the repeats) overlaps the cheapest's as ties.
void markTies(std::vector<Pick>& picks, int best);

// How wide the timings behind a tie are: the ties of the cheapest pick `best`
// (markTies) and the largest spread, max / min CPU time of the repeats, among
// it and them. A tie whose spread exceeds SurveySettings::noisySpread says
// more about the machine's load than about the integrators.
struct TimingSpread {
  int ties = 0;
  double spread = 1.0;
  double lo = 0.0, hi = 0.0;  // the range of that widest spread, CPU s per simulated s
};
TimingSpread timingSpread(const std::vector<Pick>& picks, int best);

// The whole advice for one scene, as `particle-lab advise` and the demo's
// panel give it: surveyScene with the budget settings.targetError (the scan's
// share of settings.progress 0..0.9), then pickPerIntegrator at that budget
// (0.9..1), then the cheapest. `complete` is false when settings.cancel (or an
// interrupt) stopped it: a partial survey names no pick.
struct Advice {
  Survey survey;
  std::vector<Pick> picks;  // one per survey.integrators
  int best = -1;            // index of the cheapest pick, −1 if none meets the budget
  bool complete = false;
};
Advice advise(const std::function<scenes::Scene()>& build, const SurveySettings& settings,
              const ClosedForm& closedForm = {});

// The command line that reproduces a pick: "--integrator NAME --dt X [--tolerance Y]".
std::string pickArguments(const Candidate& c);

}  // namespace lab
