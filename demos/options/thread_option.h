#pragma once
// --threads of particle-lab run and particle-demo: the most threads the
// engine's steps may use. The engine runs a step on them while they make it
// faster and on one thread while they do not (src/thread_use.h).
#include <string>

#include <CLI/CLI.hpp>

namespace options {

// Adds --threads N to app, read into threads (whose default is shown).
void addThreadsOption(CLI::App& app, int& threads);

// At most the CPUs of the process's affinity mask: threads beyond them only
// take turns on the same CPUs and wait for each other (1024 threads on 2
// CPUs stepped 500 times slower than one). A larger count is lowered to the
// CPU count, and `note` says so; otherwise `note` is left empty.
int threadsWithinAffinity(int requested, std::string& note);

}  // namespace options
