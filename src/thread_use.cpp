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

double mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Two empty regions: the first starts the threads (after a release they
// are created again), the second is what a step's hand-offs then cost.
ThreadUse::HandOff emptyRegionSeconds(int threads) {
  const double begin = steadySeconds();
  parallelTeam(threads, [](const Team&) {});
  const double started = steadySeconds();
  parallelTeam(threads, [](const Team&) {});
  return {started - begin, steadySeconds() - started};
}

double releasedSeconds() {
  const double begin = steadySeconds();
  releaseIdleThreads();
  return steadySeconds() - begin;
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

ThreadUse::ThreadUse() : clock(steadySeconds), handoff(emptyRegionSeconds), release(releasedSeconds) {}

// The clock is read once a step at each end: a decision uses the time the last step ended.
int ThreadUse::begin(int most, std::uint64_t structure) {
  const bool lastUntimed = untimed_;
  untimed_ = false;
  if (structure != structure_) {
    structure_ = structure;
    nothingToShare_ = false;
    untimed_ = !lastUntimed;
  }
  if (most != most_) {  // a new setting: start over on one thread, probing once the history is in
    most_ = most;
    present_ = 1;
    presentTimes_.clear();
    probing_ = false;
    probeTimes_.clear();
    otherMean_ = -1.0;
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
      probeStart_ = 0.0;
      if (present_ == 1) {
        const HandOff times = handoff(most);
        probeStart_ = times.start + times.trip;
        previous_ = most;
        if (times.trip > settings.handoff * median(presentTimes_)) {
          probing_ = false;
          now_ += probeStart_;
          lost(probeStart_);
        }
      }
    }
    threads = probing_ ? (present_ == 1 ? most : 1) : present_;
  }
  if (threads == 1 && previous_ > 1) {
    const double seconds = release();
    if (releaseCharged_) charge(seconds);  // the end of a lost probe of more threads
    else if (probing_) probeStart_ = seconds;  // the start of a probe of one thread
    releaseCharged_ = false;
  }
  threads_ = threads;
  started_ = clock();
  return threads;
}

// Once the wait after the last probe is over; on more threads also as soon
// as their steps' mean is over one thread's at the last probe.
bool ThreadUse::probeDue() const {
  if (now_ >= nextProbe_) return true;
  return present_ != 1 && (otherMean_ < 0.0 || mean(presentTimes_) > otherMean_);
}

void ThreadUse::end(bool parallel) {
  previous_ = threads_;
  if (most_ <= 1 || !settings.adaptive) return;
  now_ = clock();
  const double seconds = now_ - started_;
  if (untimed_) return;
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
    if (hopeless || probeDecided() || static_cast<int>(probeTimes_.size()) >= settings.probeSteps) finishProbe();
    return;
  }
  presentTimes_.push_back(seconds);
  if (static_cast<int>(presentTimes_.size()) > settings.history) presentTimes_.erase(presentTimes_.begin());
}

// A probe of more threads is decided once its steps so far, with every step
// left at one thread's mean over the thread count (no step is faster than
// its work shared perfectly), still make a mean over gain × one thread's.
bool ThreadUse::probeDecided() const {
  if (present_ != 1) return false;
  const double one = mean(presentTimes_);
  const double left = static_cast<double>(settings.probeSteps) - static_cast<double>(probeTimes_.size());
  double best = left * one / most_;
  for (const double t : probeTimes_) best += t;
  return best > settings.gain * one * settings.probeSteps;
}

void ThreadUse::finishProbe() {
  probing_ = false;
  const int other = present_ == 1 ? most_ : 1;
  // Means: beside a busy program the steps on more threads alternate between
  // fast and slow (a thread descheduled every other step), and what they
  // cost is their mean; a median of three can pick the fast ones.
  const double probe = mean(probeTimes_), present = mean(presentTimes_);
  const double more = present_ == 1 ? probe : present, one = present_ == 1 ? present : probe;
  const int faster = more <= settings.gain * one ? most_ : 1;
  if (faster == other) {  // the probe won: its count is kept, and the other probed after the quickest retry
    otherMean_ = present;
    present_ = other;
    presentTimes_ = probeTimes_;
    lostInARow_ = 0;
    retry_ = settings.quickestRetry;
    nextProbe_ = now_ + settings.quickestRetry;
  } else {  // it lost: its start, and its steps' time beyond the present count's
    otherMean_ = probe;
    double cost = probeStart_;
    for (const double t : probeTimes_) cost += std::max(0.0, t - present);
    lost(cost);
  }
  probeTimes_.clear();
}

// The next probe waits twice as long as the last that lost, and long
// enough for this one's cost to be at most probeShare of the time until then.
void ThreadUse::lost(double cost) {
  retry_ = lostInARow_ > 0 ? 2.0 * retry_ : settings.quickestRetry;
  ++lostInARow_;
  lostCost_ = 0.0;
  lostAt_ = now_;
  releaseCharged_ = present_ == 1;  // a probe of more threads: their release comes next
  charge(cost);
}

void ThreadUse::charge(double seconds) {
  lostCost_ += seconds;
  retry_ = std::clamp(std::max(retry_, lostCost_ / settings.probeShare), settings.quickestRetry, settings.longestRetry);
  nextProbe_ = lostAt_ + retry_;
}

}  // namespace particles
