#pragma once
// Certified safe steps. Survival is chaotic in dt: a coarse scan over a few
// starts can call a dt safe that fails at 0.7 of it on another start. A
// certificate is therefore the result of a fine descending scan (≤ 1% grid)
// over an ensemble of ≥ 10 perturbed starts that goes on below the smallest
// failure it finds until a whole decade of the grid has survived:
//
//   safe dt = the largest grid dt such that every grid dt from the scan's
//             bottom up to it survived T on every member,
//
// with the failure fraction (grid points where some member failed) in bands
// above it, so a reader sees how close to the certified step failures begin.
#include <functional>
#include <optional>
#include <vector>

#include "lab/failure.h"
#include "lab/scan.h"

namespace lab {

struct CertifySettings {
  double top = 0.5;          // the scan starts here and descends
  double resolution = 0.01;  // grid neighbours 1 + resolution apart (scan.h stepGrid)
  int members = 10;          // starts per grid dt: member 0 and perturbed copies (perturbStart)
  double decades = 1.0;      // survival demanded below the smallest failure (below `top` if none)
  double floor = 0.0;        // no dt below this is run (a step budget: T / floor steps per run)
  // Band edges as multiples of the safe dt: (1, 1.1], (1.1, 1.25], ...
  std::vector<double> bandEdges = {1.0, 1.1, 1.25, 1.5, 2.0};
};

// Failures among the grid points of (lo, hi] × safe dt.
struct FailureBand {
  double lo = 0.0, hi = 0.0;
  int points = 0, failed = 0;
  double fraction() const { return points > 0 ? static_cast<double>(failed) / points : 0.0; }
};
template <class Io>
void fields(Io& io, FailureBand& b) {
  io("lo", b.lo), io("hi", b.hi), io("points", b.points), io("failed", b.failed);
}

struct Certificate {
  double safeDt = 0.0;             // 0: every grid dt down to the floor failed
  double smallestFailureDt = 0.0;  // 0: nothing failed (safeDt is then the grid's top, a lower bound)
  Failure smallestFailure = Failure::None;
  double lowest = 0.0, highest = 0.0;  // the scanned part of the grid
  int points = 0;                  // grid dts scanned
  long runs = 0;                   // member runs made
  bool fullDecades = false;        // the survival below the smallest failure spans `decades`
                                   // (false: the floor ended the scan first)
  std::vector<FailureBand> bands;  // above safeDt (empty when safeDt is 0)
  bool aboveGrid() const { return smallestFailureDt == 0.0; }
  bool belowFloor() const { return safeDt == 0.0; }
};
template <class Io>
void fields(Io& io, Certificate& c) {
  io("safe_dt", c.safeDt), io("smallest_failure_dt", c.smallestFailureDt), io("smallest_failure", c.smallestFailure);
  io("lowest", c.lowest), io("highest", c.highest), io("points", c.points), io("runs", c.runs);
  io("full_decades", c.fullDecades), io("bands", c.bands);
}

// One run of member `member` at `dt` to T; nullopt when an interrupt cut it short.
using MemberRun = std::function<std::optional<Probe>(double dt, int member)>;

// The descending scan: at each grid dt from `top` down, members 0, 1, ...
// until one fails (the dt fails) or all survive; stops once the survival
// below the smallest failure spans `decades`, or at the floor. nullopt if an
// interrupt cut it short.
std::optional<Certificate> certifySafeStep(const MemberRun& run, double duration, const CertifySettings& settings);

// "< floor" when every dt down to the floor failed, "≥ top" when nothing
// failed, the safe dt otherwise (4 significant digits: the 1% grid's),
// marked " †" when the floor ended the scan before a whole `decades` below
// the smallest failure had survived (a certificate of the scanned range only).
std::string certifiedText(const Certificate& certificate);

}  // namespace lab
