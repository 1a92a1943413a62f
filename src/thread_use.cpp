#include "thread_use.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "parallel_for.h"

namespace particles {

namespace {

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The second of two empty regions: the first starts the threads (after a
// release they are created again), the second is what a step's hand-offs
// then cost.
double emptyRegionSeconds(int threads) {
  parallelTeam(threads, [](const Team&) {});
  const double start = steadySeconds();
  parallelTeam(threads, [](const Team&) {});
  return steadySeconds() - start;
}

std::string shortest(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// Called each step: the message is only built for a bad value.
void require(bool ok, const char* field, double value, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("thread use ") + field + " must be " + what + ", got " + shortest(value));
}

}  // namespace

void ThreadUseSettings::validate() const {
  require(gain > 0.0 && gain <= 1.0, "gain", gain, "in (0, 1]");
  require(history >= 1, "history", history, ">= 1");
  require(probeSteps >= 1, "probe steps", probeSteps, ">= 1");
  require(abandon > 1.0, "abandon", abandon, "> 1");
  require(handoff > 0.0, "handoff", handoff, "> 0");
  require(probeShare > 0.0 && probeShare <= 1.0, "probe share", probeShare, "in (0, 1]");
  require(quickestRetry >= 0.0, "quickest retry", quickestRetry, ">= 0 s");
  if (!(longestRetry >= quickestRetry))
    require(false, "longest retry", longestRetry, (">= the quickest retry (" + shortest(quickestRetry) + " s)").c_str());
}

ThreadUse::ThreadUse() : clock(steadySeconds), handoff(emptyRegionSeconds) {}

// The clock is read once a step at each end: a decision uses the time the last step ended.
int ThreadUse::begin(int most, std::uint64_t structure) {
  if (structure != structure_) {
    structure_ = structure;
    nothingToShare_ = false;
  }
  if (most != most_) {  // a new setting: start over on one thread, probing once the history is in
    most_ = most;
    present_ = 1;
    presentTimes_.clear();
    probing_ = false;
    probeTimes_.clear();
    otherMedian_ = -1.0;
    nextProbe_ = -std::numeric_limits<double>::infinity();
    retry_ = settings.quickestRetry;
    lostInARow_ = 0;
  }
  int threads = 1;
  if (most > 1 && !settings.adaptive) {
    threads = most;
  } else if (most > 1) {
    if (!probing_ && !nothingToShare_ && static_cast<int>(presentTimes_.size()) >= settings.history && probeDue()) {
      probing_ = true;
      if (present_ == 1) {
        const double trip = handoff(most);
        previous_ = most;
        if (trip > settings.handoff * median(presentTimes_)) {
          probing_ = false;
          now_ += trip;
          lost(trip);
        }
      }
    }
    threads = probing_ ? (present_ == 1 ? most : 1) : present_;
  }
  release_ = threads == 1 && previous_ > 1;
  threads_ = threads;
  started_ = clock();
  return threads;
}

// On one thread: once the wait after the last probe is over. On more: as
// soon as their steps are no faster than one thread's were at the last probe.
bool ThreadUse::probeDue() const {
  if (present_ == 1) return now_ >= nextProbe_;
  return otherMedian_ < 0.0 || median(presentTimes_) > otherMedian_;
}

void ThreadUse::end(bool parallel) {
  previous_ = threads_;
  if (most_ <= 1 || !settings.adaptive) return;
  now_ = clock();
  const double seconds = now_ - started_;
  if (threads_ > 1 && !parallel) {  // nothing to share: one thread, no more probes for this structure
    nothingToShare_ = true;
    probing_ = false;
    probeTimes_.clear();
    present_ = 1;
    return;
  }
  if (probing_) {
    probeTimes_.push_back(seconds);
    const bool hopeless = seconds > settings.abandon * median(presentTimes_);
    if (hopeless || static_cast<int>(probeTimes_.size()) >= settings.probeSteps) finishProbe();
    return;
  }
  presentTimes_.push_back(seconds);
  if (static_cast<int>(presentTimes_.size()) > settings.history) presentTimes_.erase(presentTimes_.begin());
}

void ThreadUse::finishProbe() {
  probing_ = false;
  const int other = present_ == 1 ? most_ : 1;
  const double probe = median(probeTimes_), present = median(presentTimes_);
  const double more = present_ == 1 ? probe : present, one = present_ == 1 ? present : probe;
  const int faster = more <= settings.gain * one ? most_ : 1;
  if (faster == other) {
    otherMedian_ = present;
    present_ = other;
    presentTimes_ = probeTimes_;
  } else {
    otherMedian_ = probe;
  }
  if (present_ == most_) {
    lostInARow_ = 0;
  } else if (other == most_) {
    double cost = 0.0;  // the probe's steps' time beyond one thread's
    for (const double t : probeTimes_) cost += std::max(0.0, t - one);
    lost(cost);
  } else {
    nextProbe_ = now_ + settings.quickestRetry;  // one thread just won a probe from more
  }
  probeTimes_.clear();
}

// The next probe waits twice as long as the last that lost, and long
// enough for this one's cost to be at most probeShare of the time until then.
void ThreadUse::lost(double cost) {
  const double doubled = lostInARow_ > 0 ? 2.0 * retry_ : settings.quickestRetry;
  retry_ = std::clamp(std::max(doubled, cost / settings.probeShare), settings.quickestRetry, settings.longestRetry);
  ++lostInARow_;
  nextProbe_ = now_ + retry_;
}

}  // namespace particles
