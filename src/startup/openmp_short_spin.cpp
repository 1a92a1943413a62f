// Compiled into every executable that links the engine (src/CMakeLists.txt),
// not into the library: a shared library may not have a .preinit_array.
//
// libgomp's idle threads spin 300000 pauses after every parallel region
// before they sleep (7 ms of CPU a region on a 2-core EPYC VM, 3 ms or more
// on bare metal), on a core a busy program or the stepping thread needs:
// beside one busy program steps on two threads stalled for 60–200 ms. With
// more threads than CPUs libgomp spins 100 pauses only (its documented rule:
// GOMP_SPINCOUNT in libgomp's manual), and it counts the CPUs once, as it is
// initialised. So this executable narrows its CPU affinity to one CPU before
// any library is initialised (its .preinit_array, which the dynamic loader
// runs first) and restores it before its own constructors run: libgomp counts
// one CPU, and the engine's teams spin briefly, then sleep. The main thread
// and every thread started later have the full affinity again; OpenMP's
// default team size becomes one, which no engine region uses (each names its
// count). The environment's OMP_WAIT_POLICY or GOMP_SPINCOUNT, when set, is
// the user's choice, and then nothing is changed.
#if defined(_OPENMP) && defined(__linux__)
#include <sched.h>

#include <initializer_list>

namespace {

cpu_set_t gStarted;       // the affinity the program started with
bool gNarrowed = false;

void narrowWhileLibrariesStart(int, char**, char** env) {
  for (char** e = env; *e; ++e)  // the environment the loader passes: the C library sets its own up later
    for (const char* name : {"OMP_WAIT_POLICY=", "GOMP_SPINCOUNT="}) {
      int k = 0;
      while (name[k] && (*e)[k] == name[k]) ++k;
      if (!name[k]) return;
    }
  if (sched_getaffinity(0, sizeof gStarted, &gStarted) != 0 || CPU_COUNT(&gStarted) < 2) return;
  cpu_set_t one;
  CPU_ZERO(&one);
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
    if (CPU_ISSET(cpu, &gStarted)) {
      CPU_SET(cpu, &one);
      break;
    }
  gNarrowed = sched_setaffinity(0, sizeof one, &one) == 0;
}

__attribute__((section(".preinit_array"), used)) void (*const kNarrow)(int, char**, char**) =
    narrowWhileLibrariesStart;

// After every shared library's initialisation, before the program's other constructors.
__attribute__((constructor(101))) void restoreAfterLibrariesStarted() {
  if (gNarrowed) sched_setaffinity(0, sizeof gStarted, &gStarted);
}

}  // namespace
#endif
