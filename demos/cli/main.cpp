// particle-lab: the headless runner. Subcommands are listed in one table;
// errors become one line on stderr and an exit code (cli::ExitCode).
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include "cli/command.h"
#include "options/usage.h"
#include "output/output_file.h"
#include "particles/cancel.h"
#include "scene_file/json_node.h"

namespace {

// Every subcommand, in the order --help lists them.
constexpr cli::Command (*kCommands[])(CLI::App&) = {
    cli::addRunCommand,
    cli::addListCommand,
    cli::addExportCommand,
    cli::addStabilityCommand,
    cli::addTimingCommand,
    cli::addAccuracyCommand,
    cli::addExtremesCommand,
    cli::addClaimsCommand,
    cli::addCostCommand,
    cli::addLongtimeCommand,
    cli::addAdviseCommand,
    cli::addSmallStepsCommand,
    cli::addRenderReportCommand,
    cli::addMergeCommand,
};

// One line on stderr (control characters escaped), and the exit code.
int fail(const std::string& message, int code = cli::kBadInput) {
  options::printErrorLine("particle-lab", message);
  return code;
}

}  // namespace

namespace cli {

int runCommandLine(const std::vector<std::string>& given, const Context& context) {
  CLI::App app{"particle-lab: run particle-system scenes without a window, list and export them, and run the laboratory's experiments"};
  app.name("particle-lab");
  app.require_subcommand(1);
  app.set_version_flag("--version", options::versionLine("particle-lab"));
  std::vector<cli::Command> commands;
  for (auto add : kCommands) commands.push_back(add(app));
  std::vector<std::string> reversed(given.rbegin(), given.rend());  // CLI11 takes them last first
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() != 0) return fail(e.what());
    app.exit(e);  // --help, --version: their text is the result
    if (const std::string error = options::flushStandardOutput(); !error.empty()) return fail(error, cli::kWriteFailed);
    return cli::kSuccess;
  }
  for (const cli::Command& command : commands) {
    if (!command.app->parsed()) continue;
    try {
      const int code = command.run(context);
      // The summary or table on stdout is the command's result: a failed write
      // of it (stdout on a full disk, /dev/full) is a failed output, exit 4.
      if (const std::string error = options::flushStandardOutput(); !error.empty()) return fail(error, cli::kWriteFailed);
      return code;
    } catch (const scenes::SceneFileError& e) {
      return fail(e.what());
    } catch (const std::invalid_argument& e) {
      return fail(e.what());
    } catch (const output::WriteError& e) {
      return fail(e.what(), cli::kWriteFailed);
    } catch (const std::bad_alloc&) {
      return fail("out of memory (the scene or the run is too large for this machine)", cli::kBadInput);
    } catch (const particles::Cancelled&) {  // a signal while a scene file was read
      return fail("interrupted while reading the scene: nothing was run or written", cli::kInterrupted);
    }
  }
  return fail("no subcommand given");
}

}  // namespace cli

int main(int argc, char** argv) { return cli::runCommandLine(std::vector<std::string>(argv + 1, argv + argc)); }
