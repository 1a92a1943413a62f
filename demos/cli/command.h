#pragma once
// The subcommands of particle-lab. Each lives in its own file and adds itself
// to the application through one add function listed in main.cpp; it returns
// the action main runs when that subcommand was given.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "options/usage.h"

namespace lab {
class Cells;
}

namespace cli {

enum ExitCode : int {
  kSuccess = 0,
  kBadInput = options::kBadUsageExit,  // a bad option value, a missing or malformed scene file
  kDiverged = 3,  // the state or its diagnostics became non-finite during a run
  kWriteFailed = options::kWriteFailedExit,  // an output file could not be written (disk full, I/O error)
  kCannotCertify = 5,  // advise: the scene's reference cannot certify any integrator within E over T
  kInterrupted = 130,  // SIGINT, SIGTERM or SIGHUP: stopped at a step boundary, outputs complete
};

// A bad option value or combination found after parsing; exits kBadInput.
using options::UsageError;

// What a subcommand runs under besides its options: a merge running an
// experiment again hands it the cells the shards recorded.
struct Context {
  std::shared_ptr<lab::Cells> replay;  // null: compute the cells
};

struct Command {
  CLI::App* app;                               // the subcommand
  std::function<int(const Context&)> run;      // returns the exit code; throws UsageError,
                                               // std::invalid_argument or SceneFileError for bad input
};

Command addRunCommand(CLI::App& app);
Command addListCommand(CLI::App& app);
Command addExportCommand(CLI::App& app);
// The laboratory (cli/lab_commands.cpp).
Command addStabilityCommand(CLI::App& app);
Command addTimingCommand(CLI::App& app);
Command addAccuracyCommand(CLI::App& app);
Command addExtremesCommand(CLI::App& app);
Command addClaimsCommand(CLI::App& app);
Command addAdviseCommand(CLI::App& app);
Command addCostCommand(CLI::App& app);
Command addLongtimeCommand(CLI::App& app);
Command addSmallStepsCommand(CLI::App& app);
Command addRenderReportCommand(CLI::App& app);
Command addMergeCommand(CLI::App& app);

// Parses `arguments` (the subcommand first) and runs that subcommand under
// `context`: particle-lab's main, and merge running an experiment again.
int runCommandLine(const std::vector<std::string>& arguments, const Context& context = {});

}  // namespace cli
