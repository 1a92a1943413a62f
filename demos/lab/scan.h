#pragma once
// Safe step-size boundaries by scanning a fine log grid of dt, never by
// bisection: survival is not monotone in dt (an integrator can fail at one dt
// and survive a larger one), so only a scan shows where every smaller step
// survives, and the islands of survival above the first failure.
#include <functional>
#include <optional>
#include <vector>

#include "lab/failure.h"

namespace lab {

// Geometric grid of step sizes in [lo, hi], neighbours in the ratio
// 2^(1/m) with m = ceil(ln 2 / ln(1 + resolution)) (so it resolves
// `resolution`), anchored so that anchor·2^j lies on it: with anchor 0.05 the
// grid holds 0.05, 0.1, 0.2 exactly, the steps of Table 1.
std::vector<double> stepGrid(double lo, double hi, double resolution = 0.05, double anchor = 0.05);

// m, the grid's steps per octave for a resolution: ceil(ln 2 / ln(1 + resolution)).
int stepsPerOctave(double resolution);

// stepGrid with every dt moved to the nearest T/n (n whole, at least 1), so a
// run of n steps ends exactly at T; points that fall together are kept once.
std::vector<double> stepGridDividing(double duration, double lo, double hi, double resolution = 0.05,
                                     double anchor = 0.05);

// A run's maxima up to a checkpoint time: max |C|/r and max (E − E(0)) / E_s.
struct Maxima {
  double time = 0.0, stretch = 0.0, rise = 0.0;
};
template <class Io>
void fields(Io& io, Maxima& m) {
  io("time", m.time), io("stretch", m.stretch), io("rise", m.rise);
}

// One run of one ensemble member at one dt, stopped at its first failure.
struct Probe {
  bool failed = false;
  Failure failure = Failure::None;
  double time = 0.0;         // simulated time reached (the failing step's time when failed)
  double maxRelativeStretch = 0.0;
  double maxEnergyRise = 0.0;  // max (E − E(0)) / E_s
  std::vector<Maxima> maximaAt;  // the maxima up to each checkpoint the run reached (runMember's checkpoints)
  bool survives(double duration, double dt) const { return !failed || time > duration + 0.5 * dt; }
  // The maxima over [0, duration]: a checkpoint's when one was kept there, else the whole run's.
  Maxima maximaUpTo(double duration, double dt) const;
};
// The fields a cell's result keeps (lab/cell_json.h).
template <class Io>
void fields(Io& io, Probe& p) {
  io("failed", p.failed), io("failure", p.failure), io("time", p.time);
  io("max_relative_stretch", p.maxRelativeStretch), io("max_energy_rise", p.maxEnergyRise);
  io("maxima_at", p.maximaAt);
}

// Every run of a scan, in the order made: ascending dt, members 0.. at each.
struct ScanRun {
  double dt;
  int member;
  Probe probe;
};
template <class Io>
void fields(Io& io, ScanRun& r) {
  io("dt", r.dt), io("member", r.member), io("probe", r.probe);
}

struct ScanSettings {
  std::vector<double> grid;          // ascending (stepGrid)
  int members = 3;                   // ensemble: member 0 and members perturbed by perturbStart
  std::vector<double> durations;     // the T to evaluate; runs go to the largest
  double beyond = 2.0;               // keep scanning up to beyond × the first failure at the shortest T
  int extendDecades = 0;             // scanSafeStep: when the smallest grid dt fails, rescan from a grid
                                     // 10× lower, at most this many times
};

// Runs the scan: at each grid dt member 0, then the other members unless one
// already failed before the shortest T (every T then fails at this dt). Stops
// past beyond × the first failure at the shortest T, or at the grid's end.
// run(dt, member, duration) makes one run. nullopt if an interrupt cut it short.
std::optional<std::vector<ScanRun>> scanSteps(const std::function<std::optional<Probe>(double, int, double)>& run,
                                               const ScanSettings& settings);

// Survival of every member at one grid dt for one T: the scan's verdict there.
struct GridSurvival {
  double dt;
  bool survived;                  // every member survived T
  int membersRun = 0, survivors = 0;
  Failure failure = Failure::None;  // what fired first (earliest failure) when not survived
  double maxRelativeStretch = 0.0, maxEnergyRise = 0.0;  // over the members' runs up to this T
};
std::vector<GridSurvival> survivalAt(const std::vector<ScanRun>& runs, double duration, int members);

// What a scan says about one T.
struct Boundary {
  double safeDt = 0.0;          // largest grid dt at and below which every grid dt survived; 0: the smallest failed
  double firstFailureDt = 0.0;  // smallest grid dt that failed; 0: none on the scanned grid
  Failure firstFailure = Failure::None;
  std::vector<double> survivalAbove;  // grid dts above the first failure where every member survived
  double lowest = 0.0, highest = 0.0;  // the scanned part of the grid
  bool belowGrid() const { return safeDt == 0.0; }
  bool aboveGrid() const { return firstFailureDt == 0.0; }  // safeDt is then the grid's top: a lower bound
};
template <class Io>
void fields(Io& io, Boundary& b) {
  io("safe_dt", b.safeDt), io("first_failure_dt", b.firstFailureDt), io("first_failure", b.firstFailure);
  io("survival_above", b.survivalAbove), io("lowest", b.lowest), io("highest", b.highest);
}
Boundary boundaryOf(const std::vector<GridSurvival>& survival);

// Grid points that survived below the first failure (all of them if nothing failed):
// how firmly the scanned part of the grid supports safeDt.
int survivorsBelowFirstFailure(const std::vector<GridSurvival>& survival);

}  // namespace lab
