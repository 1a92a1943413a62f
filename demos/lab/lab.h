#pragma once
// The laboratory: experiments that measure the speed–accuracy trade and the
// stability of each integrator, writing CSVs and readable tables.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "scene.h"
#include "lab/failure.h"
#include "lab/scan.h"
#include "particles/integrator.h"

namespace lab {

// Threads used when --jobs is not given: every core (at least one).
int defaultJobs();

// Options shared by every experiment subcommand.
struct LabOptions {
  std::string outDir = "lab-out";  // CSVs and tables are written here
  bool quick = false;              // small grids, short runs: proves the code runs
  std::vector<std::string> integrators;  // empty: every integrator in the table
  int jobs = defaultJobs();        // threads for independent sweep cells (parallel.h)
  FailureCriterion criterion;      // when a run counts as failed (failure.h)
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
  bool blewUp() const { return failed && isBlowUp(failure); }
};

// Steps the scene with the integrator for `duration` simulated seconds
// (round(duration/dt) steps), stopping at the first failure by `criterion` or
// at an interrupt (then cutShort is set and callers discard the result).
// `observe` (optional) runs after each step that did not fail; returning
// false ends the run there (RunResult::stopped).
RunResult simulate(scenes::Scene& scene, particles::Integrator& integrator, double dt,
                   double duration, const FailureCriterion& criterion = {},
                   const std::function<bool(const particles::ParticleSystem&)>& observe = {});

// One scan run: ensemble member `member` (perturbStart) of a freshly built
// scene under the integrator for `duration`; nullopt when an interrupt (or
// `cancel`, checked every step) cut it short.
std::optional<Probe> runMember(const std::function<scenes::Scene()>& build, const std::string& integrator,
                               double dt, int member, double duration, const FailureCriterion& criterion,
                               const std::atomic<bool>* cancel = nullptr);

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

// Integrators selected by the options, in table order.
std::vector<std::string> selectedIntegrators(const LabOptions& options);

// Log-spaced values from lo to hi inclusive.
std::vector<double> logSpace(double lo, double hi, int count);

// Least-squares slope of log y against log x (points with y ≤ 0 are skipped).
double logLogSlope(const std::vector<double>& x, const std::vector<double>& y);

// Median of a non-empty sample.
double median(std::vector<double> values);

// A CSV file written row by row and flushed after every row, so an
// interrupted experiment keeps what it measured.
class Csv {
 public:
  Csv(const std::string& path, const std::vector<std::string>& columns);
  Csv& operator<<(const std::string& cell);
  Csv& operator<<(double value);
  Csv& operator<<(long value);
  Csv& operator<<(int value) { return *this << static_cast<long>(value); }
  void endRow();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ofstream out_;
  std::size_t columns_, cell_ = 0;
};

// Writes a Markdown table under its title in italics (also printed to stdout) to DIR/NAME.md.
void writeTable(const LabOptions& options, const std::string& name, const std::string& title,
                const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);

// Appends key,value pairs that the report quotes to DIR/values.csv.
void recordValue(const LabOptions& options, const std::string& key, const std::string& value);

std::string fixed(double value, int digits);
std::string general(double value, int digits = 3);

// Progress on stderr: done/total, elapsed, estimated time left (at most every 2 s).
class Progress {
 public:
  Progress(std::string label, long total);
  void tick(long count = 1);  // safe from several threads
  ~Progress();

 private:
  std::mutex mutex_;
  std::string label_;
  long total_, done_ = 0;
  std::chrono::steady_clock::time_point start_, lastPrint_;
};

// Set by SIGINT/SIGTERM once installInterruptHandler() ran; loops stop early.
void installInterruptHandler();
bool interrupted();

// Creates the output directory (and parents).
void prepareOutput(const LabOptions& options);

}  // namespace lab
