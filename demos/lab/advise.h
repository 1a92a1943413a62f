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

#include "lab/lab.h"
#include "lab/reference.h"

namespace lab {

// Bounds of the survey's inputs: a reference tolerance below this runs for
// minutes with no gain (rounding bounds the error there, as for dopri5's
// --tolerance).
inline constexpr double kMinReferenceTolerance = 1e-13;

// The reference holds T / interval samples, each of them the positions,
// velocities and accelerations of every particle (three Eigen vectors of 2n
// doubles, each with its handle and the allocator's header: 16 + 16n + 16
// bytes) and the energy: 48 n + 104 bytes a sample. A survey whose reference
// would take more than kMaxReferenceBytes is refused before it starts (a
// limit on samples alone let a one-particle scene reach 3.9 GB: 160 bytes a
// sample, of which 16 are the particle's position).
inline constexpr double kMaxReferenceBytes = 1e9;
double referenceBytes(double samples, std::size_t particles);

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
  // Certification of each pick (certifyPick): every dt of a grid certifyResolution apart in
  // [safeFraction × dt, dt / safeFraction] (tolerances: [safeFraction × tol, tol / safeFraction])
  // survives T on certifyMembers starts, and a tolerance's error stays within the budget across it.
  int certifyMembers = 10;          // 0: picks are not certified
  double certifyResolution = 0.01;
  bool certifyAll = false;          // every pick; else the cheapest and its ties (a pick that moves
                                    // is timed again, and the cheapest certified pick wins)
  FailureCriterion failure;         // the failure criterion (lab/failure.h)
  double referenceTolerance = 1e-11;  // odeint's, in [kMinReferenceTolerance, 1]; the check run uses 100× this
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
  bool touchedWall = false;          // the reference passed through a wall (contacts ignored)
  int particles = 0;
  // Why no integrator can be certified within E over T, empty if one can:
  // the references part by more than E/10 before T (chaos: the scene is not
  // predictable that long at that error), or the reference meets a contact it
  // does not model. Then no integrator is scanned, and certifiableHorizon is
  // the longest T from 0 over which the reference still holds.
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
// Throws Cancelled once `cancel` is set.
Reference makeReference(const std::function<scenes::Scene()>& build, double horizon, double interval,
                        double tolerance, const ClosedForm& closedForm = {},
                        const std::atomic<bool>* cancel = nullptr);

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
  Candidate candidate;
  double cpuPerSimulatedSecond = 0.0, cpuMin = 0.0, cpuMax = 0.0;  // median and spread of repeats
  // The certified window around the pick (dt, or the tolerance of an adaptive
  // scheme): every grid point in [certifiedLo, certifiedHi] survived on every
  // start; 0 when not certified. certifyRuns: the runs it took (the picks moved
  // down past failures included).
  double certifiedLo = 0.0, certifiedHi = 0.0;
  long certifyRuns = 0;
  std::string uncertified;  // why no pick could be certified ("" when one was or none was tried)
  bool tie = false;         // within the timing spread of the cheapest (their repeats' ranges overlap)
};
template <class Io>
void fields(Io& io, Pick& p) {
  io("found", p.found), io("candidate", p.candidate), io("cpu_per_simulated_second", p.cpuPerSimulatedSecond);
  io("cpu_min", p.cpuMin), io("cpu_max", p.cpuMax), io("certified_lo", p.certifiedLo);
  io("certified_hi", p.certifiedHi), io("certify_runs", p.certifyRuns), io("uncertified", p.uncertified);
  io("tie", p.tie);
}

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
