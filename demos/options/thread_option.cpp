#include "options/thread_option.h"

#include "options/option_checks.h"
#include "particles/threads.h"

namespace options {

void addThreadsOption(CLI::App& app, int& threads) {
  app.add_option("--threads", threads,
                 "the most threads of the engine's parallel loops, a decimal integer in [1, 1024]; more than the "
                 "CPUs of the affinity mask are lowered to that count, with a note on stderr. A step runs on them "
                 "while they make it faster and on one thread while they do not (on a machine busy with other "
                 "programs); the results are the same on any count; 1 starts no thread (default: the CPUs of "
                 "the affinity mask)")
      ->capture_default_str()
      ->check(decimalInteger(1, 1024));
}

int threadsWithinAffinity(int requested, std::string& note) {
  note.clear();
  const int cpus = particles::affinityCpuCount();
  if (requested <= cpus) return requested;
  note = "--threads " + std::to_string(requested) + " is more than the " + std::to_string(cpus) + " CPU" +
         (cpus == 1 ? "" : "s") + " this process may run on (its affinity mask): using " + std::to_string(cpus);
  return cpus;
}

}  // namespace options
