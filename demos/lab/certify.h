#pragma once
// Safe steps as failure bounds. Survival is chaotic in dt: a coarse scan over
// a few starts can call a dt safe that fails at 0.7 of it on another start,
// and no finite scan proves that a step never fails. What a scan can give is
// a step together with what its runs support. The scan here descends a fine
// grid (≤ 1% apart) over an ensemble of ≥ 10 perturbed starts and goes on
// below the smallest failure it finds until a whole decade of the grid has
// survived:
//
//   survived dt = the largest grid dt such that it and every grid dt below it,
//                 down to the scan's bottom, survived T on every start;
//
//   its bound   = the Clopper–Pearson upper bound (failure_bound.h) on the
//                 per-run failure probability from the N runs at and below it,
//                 none of which failed: p ≤ 1 − 0.05^(1/N) ≈ 3/N at 95%
//                 confidence, for a start perturbed like the ensemble's and a
//                 dt drawn from the grid's range below the survived dt;
//
// with the measured failure fraction (failed runs / runs) in bands below and
// above it, so a reader sees how close to the step failures begin. Above the
// survived dt every start is run at every grid dt up to the last band, so
// those fractions count runs, not the first failing start.
#include <functional>
#include <optional>
#include <vector>

#include "lab/failure.h"
#include "lab/failure_bound.h"
#include "lab/scan.h"

namespace lab {

struct CertifySettings {
  double top = 0.5;          // the scan starts here and descends
  double resolution = 0.01;  // grid neighbours 1 + resolution apart (scan.h stepGrid)
  int members = 10;          // starts per grid dt: member 0 and perturbed copies (perturbStart)
  double decades = 1.0;      // survival demanded below the smallest failure (below `top` if none)
  double floor = 0.0;        // no dt below this is run (a step budget: T / floor steps per run)
  // Band edges as multiples of the survived dt: (0.1, 0.5], (0.5, 1], (1, 1.1], ...
  std::vector<double> bandEdges = {0.1, 0.5, 1.0, 1.1, 1.25, 1.5, 2.0};
};

// The starts per grid dt whose runs over `decades` of the grid (resolution
// apart) reach runsForBound(bound): at least `settings.members`.
int membersForBound(const CertifySettings& settings, double bound);

// Runs and failures at the grid points of (lo, hi] × the survived dt.
struct FailureBand {
  double lo = 0.0, hi = 0.0;
  int points = 0, failedPoints = 0;  // grid dts, and those where some start failed
  FailureCount runs;                 // every run made there
};
template <class Io>
void fields(Io& io, FailureBand& b) {
  io("lo", b.lo), io("hi", b.hi), io("points", b.points), io("failed_points", b.failedPoints), io("runs", b.runs);
}

struct Certificate {
  double survivedDt = 0.0;         // 0: every grid dt down to the floor failed
  double smallestFailureDt = 0.0;  // 0: nothing failed (survivedDt is then the grid's top, a lower bound)
  Failure smallestFailure = Failure::None;
  double lowest = 0.0, highest = 0.0;  // the scanned part of the grid
  int points = 0;                  // grid dts scanned
  long runs = 0;                   // member runs made
  bool fullDecades = false;        // the survival below the smallest failure spans `decades`
                                   // (false: the floor ended the scan first)
  FailureCount atAndBelow;         // the runs at and below survivedDt (none failed)
  std::vector<FailureBand> bands;  // around survivedDt (empty when survivedDt is 0)
  // The bound the runs at and below the survived dt support (1 when there are none).
  double bound() const { return atAndBelow.upperBound(); }
  bool aboveGrid() const { return smallestFailureDt == 0.0; }
  bool belowFloor() const { return survivedDt == 0.0; }
};
template <class Io>
void fields(Io& io, Certificate& c) {
  io("survived_dt", c.survivedDt), io("smallest_failure_dt", c.smallestFailureDt);
  io("smallest_failure", c.smallestFailure), io("lowest", c.lowest), io("highest", c.highest);
  io("points", c.points), io("runs", c.runs), io("full_decades", c.fullDecades), io("at_and_below", c.atAndBelow);
  io("bands", c.bands);
}

// One run of member `member` at `dt` to T; nullopt when an interrupt cut it short.
using MemberRun = std::function<std::optional<Probe>(double dt, int member)>;

// The descending scan: at each grid dt from `top` down, members 0, 1, ...
// until one fails (the dt fails) or all survive; stops once the survival
// below the smallest failure spans `decades`, or at the floor. Then every
// start not yet run at the grid dts above the survived dt, up to the last
// band edge, is run. nullopt if an interrupt cut it short.
std::optional<Certificate> certifySafeStep(const MemberRun& run, double duration, const CertifySettings& settings);

// "< floor" when every dt down to the floor failed, "≥ top" when nothing
// failed, the survived dt otherwise (4 significant digits: the 1% grid's),
// marked " †" when the floor ended the scan before a whole `decades` below
// the smallest failure had survived (a statement about the scanned range only).
std::string survivedText(const Certificate& certificate);

// survivedText with its bound: "0.07001 (p ≤ 0.0013)".
std::string survivedWithBoundText(const Certificate& certificate);

}  // namespace lab
