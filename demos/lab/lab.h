#pragma once
// The laboratory: experiments that measure the speed–accuracy trade and the
// stability of each integrator, writing CSVs and readable tables.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "output/csv_writer.h"
#include "scene.h"
#include "lab/failure.h"
#include "lab/scan.h"
#include "output/format_number.h"
#include "particles/integrator.h"

namespace lab {

// Threads used when --jobs is not given: every core (at least one).
int defaultJobs();

class Cells;  // lab/cells.h
// Every cell computed, results written: an experiment run on its own.
std::shared_ptr<Cells> allCells();

// Options shared by every experiment subcommand.
struct LabOptions {
  std::string outDir = "lab-out";  // CSVs and tables are written here
  bool quick = false;              // small grids, short runs: proves the code runs
  std::vector<std::string> integrators;  // empty: every integrator in the table
  int jobs = defaultJobs();        // threads for independent sweep cells (parallel.h)
  FailureCriterion criterion;      // when a run counts as failed (failure.h)
  std::shared_ptr<Cells> cells = allCells();  // this run's cells: all, a shard's, or replayed (cells.h)
};

struct RunResult {
  bool failed = false;
  Failure failure = Failure::None;
  std::string reason;        // failureName(failure), "" while none fired
  bool cutShort = false;     // an interrupt stopped the run: not a measurement
  double time = 0.0;         // simulated time reached
  long steps = 0;
  double seconds = 0.0;      // wall time of the simulation work
  double maxRelativeStretch = 0.0;  // max over steps of max |C|/r
  double maxEnergyRise = 0.0;       // max over steps of (E − E(0)) / E_s
  particles::StepStats work{0, 0, 0.0, 0, 0, 0};  // summed over the steps taken
  double energyStart = 0.0, energyEnd = 0.0;
  double energyScale = 0.0;  // E_s, releasableEnergy() of the start
  bool stopped = false;      // the observer ended the run before T
  std::vector<Maxima> maximaAt;  // maxStretch and maxEnergyRise so far at each checkpoint reached
  bool blewUp() const { return failed && isBlowUp(failure); }
};
// The fields a cell's result keeps (lab/cell_json.h); cutShort is never kept.
template <class Io>
void fields(Io& io, RunResult& r) {
  io("failed", r.failed), io("failure", r.failure), io("reason", r.reason), io("time", r.time);
  io("steps", r.steps), io("seconds", r.seconds), io("max_relative_stretch", r.maxRelativeStretch);
  io("max_energy_rise", r.maxEnergyRise), io("solves", r.work.solves), io("cg_iterations", r.work.cgIterations);
  io("max_residual", r.work.maxResidual), io("force_evaluations", r.work.forceEvaluations);
  io("internal_steps", r.work.internalSteps), io("energy_start", r.energyStart), io("energy_end", r.energyEnd);
  io("energy_scale", r.energyScale), io("stopped", r.stopped);
}

// Steps the scene with the integrator for `duration` simulated seconds
// (round(duration/dt) steps), stopping at the first failure by `criterion` or
// at an interrupt (then cutShort is set and callers discard the result).
// `observe` (optional) runs after each step that did not fail; returning
// false ends the run there (RunResult::stopped).
// `checkpoints` (ascending times): the maxima so far are kept at each one reached (RunResult::maximaAt).
RunResult simulate(scenes::Scene& scene, particles::Integrator& integrator, double dt,
                   double duration, const FailureCriterion& criterion = {},
                   const std::function<bool(const particles::ParticleSystem&)>& observe = {},
                   const std::vector<double>& checkpoints = {});

// One scan run: ensemble member `member` (perturbStart) of a freshly built
// scene under the integrator for `duration`; nullopt when an interrupt (or
// `cancel`, checked every step) cut it short. The maxima are kept at each of
// `checkpoints` the run reaches (Probe::maximaAt).
std::optional<Probe> runMember(const std::function<scenes::Scene()>& build, const std::string& integrator,
                               double dt, int member, double duration, const FailureCriterion& criterion,
                               const std::atomic<bool>* cancel = nullptr,
                               const std::vector<double>& checkpoints = {});

// The safe boundary of one scene under one integrator at T = duration: a scan
// (scanSteps) of `settings.grid` over `settings.members` starts; nullopt when
// an interrupt cut it short.
std::optional<Boundary> scanSafeStep(const std::function<scenes::Scene()>& build, const std::string& integrator,
                                     double duration, ScanSettings settings, const FailureCriterion& criterion);

// "< lo" when even the grid's smallest dt failed, "≥ hi" when nothing on the
// scanned grid failed (a lower bound), the safe dt otherwise.
std::string safeStepText(const Boundary& boundary);

// Magnitude of the scene's gravity (0 without a gravity force).
double gravityMagnitude(const particles::ParticleSystem& system);

// Whether the laboratory's default sweeps over long chains and large scenes
// (stability, timing, cost, extremes) run the integrator named `scheme`; one
// left out is run there only when named (--integrators), and the long-time
// and accuracy experiments on small scenes run every scheme.
bool inLabSweeps(const std::string& scheme);

// Integrators selected by the options, in table order: those named by
// --integrators, else every scheme of the table (everyScheme) or those in the
// laboratory's sweeps (inLabSweeps).
std::vector<std::string> selectedIntegrators(const LabOptions& options, bool everyScheme = false);

// Log-spaced values from lo to hi inclusive.
std::vector<double> logSpace(double lo, double hi, int count);

// Least-squares slope of log y against log x (points with y ≤ 0 are skipped).
double logLogSlope(const std::vector<double>& x, const std::vector<double>& y);

// Median of a non-empty sample.
double median(std::vector<double> values);

// An experiment's CSV file DIR/NAME (output::CsvWriter, numbers to 10
// significant digits), flushed after every row so an interrupted experiment
// keeps what it measured. In a shard (cells.h) it writes nothing.
class Csv {
 public:
  Csv(const LabOptions& options, const std::string& name, const std::vector<std::string>& columns);
  ~Csv();
  Csv& operator<<(const std::string& cell);
  Csv& operator<<(double value);
  Csv& operator<<(long value);
  Csv& operator<<(int value) { return *this << static_cast<long>(value); }
  void endRow();

 private:
  std::unique_ptr<output::CsvWriter> writer_;  // null in a shard
};

// Writes a Markdown table under its title in italics (also printed to stdout) to DIR/NAME.md.
void writeTable(const LabOptions& options, const std::string& name, const std::string& title,
                const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);

// Records a value the report quotes under `key` in DIR/values.csv (lab/values.h).
void recordValue(const LabOptions& options, const std::string& key, const std::string& value);

// Numbers in tables and quoted values (format_number.h): `digits` after the
// point, or `digits` significant digits (printf's %.*f and %.*g).
inline std::string fixed(double value, int digits) { return output::formatFixed(value, digits); }
inline std::string general(double value, int digits = 3) { return output::formatGeneral(value, digits); }

// Progress on stderr: done/total, elapsed, estimated time left (at most every 2 s).
// A merge (cells.h, replay) computes nothing and shows none.
class Progress {
 public:
  Progress(const LabOptions& options, std::string label, long total);
  void tick(long count = 1);  // safe from several threads
  ~Progress();

 private:
  std::mutex mutex_;
  std::string label_;
  long total_, done_ = 0;
  const Cells* cells_;
  bool silent_;
  std::chrono::steady_clock::time_point start_, lastPrint_;
};

// Set by SIGINT/SIGTERM/SIGHUP once installInterruptHandler() ran; loops stop early.
void installInterruptHandler();
bool interrupted();

// Creates the output directory `dir` (and parents); throws std::invalid_argument
// "--out: ..." when it is empty, or cannot be created or is not a directory.
void createOutputDirectory(const std::string& dir);
// Creates options.outDir (createOutputDirectory) and, when this run writes
// its outputs, removes the experiment's quoted values (keys starting with
// `valuePrefix`) left in its values.csv by an earlier run, so that every
// value there is this run's.
void prepareOutput(const LabOptions& options, const std::string& valuePrefix);

}  // namespace lab
