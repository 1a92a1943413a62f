#pragma once
// The laboratory: experiments that measure the speed–accuracy trade and the
// stability of each integrator, writing CSVs and readable tables.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "scene.h"
#include "particles/divergence.h"
#include "particles/integrator.h"
#include "particles/step_stats.h"

namespace lab {

// Options shared by every experiment subcommand.
struct LabOptions {
  std::string outDir = "lab-out";  // CSVs and tables are written here
  bool quick = false;              // small grids, short runs: proves the code runs
  std::vector<std::string> integrators;  // empty: every integrator in the table
};

// The laboratory's thresholds for particles::checkDivergence, the one
// definition of "exploded" used by every experiment and the report. A run
// explodes at the first step where the state is not finite, the step failed,
//  - a constraint is violated by more than maxRelativeStretch of its length
//    (max |C|/r, C in length units), or
//  - the total energy exceeds its initial value by more than energyGain times
//    the scene's energy scale (energyScale below).
struct Explosion {
  double maxRelativeStretch = 0.1;
  double energyGain = 1.0;

  // The limits for a freshly built scene (its energy scale taken now).
  particles::DivergenceLimits limits(const particles::ParticleSystem& system) const;
};

struct RunResult {
  bool exploded = false;
  std::string reason;        // particles::divergenceReasonName of the explosion, or ""
  double time = 0.0;         // simulated time reached
  long steps = 0;
  double seconds = 0.0;      // wall time of the simulation work
  double maxRelativeStretch = 0.0;
  particles::StepStats work{0, 0, 0.0, 0, 0, 0};  // summed over the steps taken
  double energyStart = 0.0, energyEnd = 0.0;
};

// Steps the scene with the integrator for `duration` simulated seconds,
// stopping at the first explosion (or at an interrupt: callers then discard
// the result). `observe` (optional) runs after each step.
RunResult simulate(scenes::Scene& scene, particles::Integrator& integrator, double dt,
                   double duration, const Explosion& explosion = {},
                   const std::function<void(const particles::ParticleSystem&)>& observe = {});

// Energy scale of the explosion criterion for a freshly built scene:
// Σ m |g| D + |E(0)| + 1, with D the diagonal of the initial bounding box —
// more energy than falling the whole scene could give.
double energyScale(const particles::ParticleSystem& system);

// Magnitude of the scene's gravity (0 without a gravity force).
double gravityMagnitude(const particles::ParticleSystem& system);

// Integrators selected by the options, in table order.
std::vector<std::string> selectedIntegrators(const LabOptions& options);

// Largest x in [lo, hi] with survives(x), by bisection in log x over `rounds`
// halvings; hi if it survives, 0 if nothing does. Assumes survival is monotone.
// Surviving probes are the costly ones, so lo is probed only when every
// bisection probe failed.
double bisectStep(const std::function<bool(double)>& survives, double lo, double hi, int rounds);

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
  void tick(long count = 1);
  ~Progress();

 private:
  std::string label_;
  long total_, done_ = 0;
  std::chrono::steady_clock::time_point start_, lastPrint_;
};

// Largest dt in [lo, hi] at which a freshly built scene survives `duration`
// under the integrator (bisectStep over fresh runs); each run ticks `progress`.
double maxStableStep(const std::function<scenes::Scene()>& build, const std::string& integrator,
                     double duration, double lo, double hi, int rounds, const Explosion& explosion,
                     Progress& progress);

// Set by SIGINT/SIGTERM once installInterruptHandler() ran; loops stop early.
void installInterruptHandler();
bool interrupted();

// Creates the output directory (and parents).
void prepareOutput(const LabOptions& options);

}  // namespace lab
