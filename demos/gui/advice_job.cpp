#include "advice_job.h"

#include <cmath>
#include <new>
#include <stdexcept>

#include "lab/lab.h"

namespace demo {

const char* adviceStateName(AdviceState state) {
  switch (state) {
    case AdviceState::Idle: return "idle";
    case AdviceState::Running: return "running";
    case AdviceState::Done: return "done";
    case AdviceState::Cancelled: return "cancelled";
    case AdviceState::Failed: return "failed";
  }
  return "?";
}

const char* AdviceJob::unavailable() {
#ifdef __EMSCRIPTEN__
  return "Advice is not offered in the browser: its survey runs the scene hundreds of times (seconds to minutes) "
         "on a worker thread, and the page has one thread, which must keep drawing. particle-lab advise runs it "
         "on the desktop.";
#else
  return nullptr;
#endif
}

AdviceJob::~AdviceJob() { stop(); }

void AdviceJob::stop() {
  cancel_ = true;
  if (worker_.joinable()) worker_.join();
}

void AdviceJob::start(const SceneChoice& scene, const AdviceRequest& request) {
  if (const char* why = unavailable()) throw std::invalid_argument(why);
  if (!(std::isfinite(request.error) && request.error > 0.0))
    throw std::invalid_argument("advice: error must be > 0, got " + lab::general(request.error));
  if (!(std::isfinite(request.horizon) && request.horizon > 0.0))
    throw std::invalid_argument("advice: horizon must be > 0, got " + lab::general(request.horizon));
  stop();
  scene_ = scene;
  request_ = request;
  cancel_ = false;
  finished_ = false;
  progress_ = 0.0;
  message_.clear();
  state_ = AdviceState::Running;
  worker_ = std::thread([this, scene, request] {
    // The settings `particle-lab advise --error E --horizon T --max-steps N --repeats R --certify-starts S` uses.
    lab::SurveySettings settings;
    settings.horizon = request.horizon;
    settings.targetError = settings.abortError = request.error;
    settings.maxSteps = request.maxSteps;
    settings.repeats = request.repeats;
    settings.certifyMembers = request.certifyStarts;
    settings.cancel = &cancel_;
    settings.progress = [this](double f) { progress_ = f; };
    try {
      result_ = lab::advise([&scene] { return buildChoice(scene); }, settings);
      error_.clear();
    } catch (const std::bad_alloc&) {
      error_ = "out of memory";
    } catch (const std::exception& e) {
      error_ = e.what();
    }
    finished_ = true;
  });
}

void AdviceJob::cancel() {
  if (running()) cancel_ = true;
}

bool AdviceJob::poll() {
  if (!running() || !finished_.load()) return false;
  worker_.join();
  message_ = error_;
  if (!error_.empty()) state_ = AdviceState::Failed;
  else if (!result_.complete) state_ = AdviceState::Cancelled;
  else state_ = AdviceState::Done;
  advice_ = std::move(result_);
  result_ = {};
  return true;
}

}  // namespace demo
