#include "cli/run_progress.h"

#include <unistd.h>

namespace cli {

RunProgress::RunProgress(long long steps, bool shown, std::FILE* out)
    : steps_(steps), shown_(shown), out_(out), start_(Clock::now()), next_(start_ + std::chrono::seconds(1)) {}

bool RunProgress::stderrIsTerminal() { return isatty(STDERR_FILENO) == 1; }

void RunProgress::update(long long step, double t) {
  if (!shown_) return;
  const Clock::time_point now = Clock::now();
  if (now < next_) return;
  next_ = now + std::chrono::milliseconds(250);
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double fraction = steps_ > 0 ? static_cast<double>(step) / static_cast<double>(steps_) : 1.0;
  const double left = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  // \033[K erases the rest of a longer line drawn before.
  std::fprintf(out_, "\rparticle-lab: step %lld/%lld (%.0f%%), t = %.6g s, %.1f s elapsed, ~%.1f s left\033[K", step,
               steps_, 100.0 * fraction, t, elapsed, left);
  std::fflush(out_);
  drawn_ = true;
}

void RunProgress::erase() {
  if (!drawn_) return;
  std::fputs("\r\033[K", out_);
  std::fflush(out_);
  drawn_ = false;
}

}  // namespace cli
