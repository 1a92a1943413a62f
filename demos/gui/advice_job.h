#pragma once
// The panel's advice: lab::advise — the function `particle-lab advise` calls —
// run on a worker thread for a copy of the current scene, built from its
// source (name, preset and parameters, or file) the way the command line
// builds it, so the running simulation is never touched. The main loop polls
// it each frame and keeps drawing; cancel() and the destructor stop the worker
// at its next step and join it.
#include <atomic>
#include <string>
#include <thread>

#include "lab/advise.h"
#include "scene_keys.h"

namespace demo {

// What the panel asks: the error budget E and horizon T of `particle-lab
// advise --error E --horizon T`, and the scan's limits.
struct AdviceRequest {
  double error = 1e-3;    // E, world units: largest particle position error allowed over [0, T]
  double horizon = 10.0;  // T, simulated seconds
  long maxSteps = 20000;  // the smallest dt scanned is T / maxSteps (the command line's --max-steps)
  int repeats = 3;        // timed repeats of each pick; the median is reported
  int certifyStarts = lab::SurveySettings{}.certifyMembers;  // the command line's --certify-starts
};

enum class AdviceState { Idle, Running, Done, Cancelled, Failed };
const char* adviceStateName(AdviceState state);  // "idle", "running", ...

class AdviceJob {
 public:
  AdviceJob() = default;
  AdviceJob(const AdviceJob&) = delete;
  AdviceJob& operator=(const AdviceJob&) = delete;
  ~AdviceJob();  // cancels a running survey and joins its thread

  // Why the survey is not offered here, or null where it is. The page has
  // one thread, which must keep drawing; the survey runs a scene hundreds of
  // times (seconds to minutes) and cannot be cut into frames.
  static const char* unavailable();

  // Starts the survey of a fresh build of `scene` (a running one is cancelled
  // and joined first). Throws std::invalid_argument for a bad request (E or
  // T not finite and > 0) or where it is unavailable(), before any thread starts.
  void start(const SceneChoice& scene, const AdviceRequest& request);
  void cancel();  // asks the worker to stop; poll() sees it end
  // Joins a worker that finished; call once a frame. Returns true the frame
  // the job leaves Running.
  bool poll();

  AdviceState state() const { return state_; }
  bool running() const { return state_ == AdviceState::Running; }
  bool cancelling() const { return running() && cancel_.load(); }
  double progress() const { return progress_.load(); }  // 0..1 while running
  // Valid in Done: the survey, each integrator's pick and the cheapest.
  const lab::Advice& advice() const { return advice_; }
  const SceneChoice& scene() const { return scene_; }  // what was surveyed
  const AdviceRequest& request() const { return request_; }
  const std::string& message() const { return message_; }  // Failed: why

 private:
  void stop();  // cancel and join

  std::thread worker_;
  std::atomic<bool> cancel_{false};
  std::atomic<bool> finished_{false};  // set by the worker as its last act
  std::atomic<double> progress_{0.0};
  AdviceState state_ = AdviceState::Idle;
  SceneChoice scene_;
  AdviceRequest request_;
  // Written by the worker, read by the main thread only after the join.
  lab::Advice advice_, result_;
  std::string message_, error_;
};

}  // namespace demo
