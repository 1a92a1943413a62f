// The laboratory's subcommands: stability, timing, accuracy, extremes, claims,
// and render-report, which fills the report template from their output.
#include <cstdio>
#include <iostream>
#include <streambuf>
#include <memory>
#include <optional>

#include "cli/command.h"
#include "lab/cells.h"
#include "lab/experiments.h"
#include "lab/render.h"
#include "options/option_checks.h"
#include "output/output_file.h"
#include "output/printable.h"
#include "particles/check.h"

namespace cli {

namespace {

// Options every experiment takes, with --shard; held by the returned action.
struct ExperimentOptions : lab::LabOptions {
  std::string shard;  // "K/N", empty: every cell
};

std::shared_ptr<ExperimentOptions> addLabOptions(CLI::App* command) {
  auto options = std::make_shared<ExperimentOptions>();
  command->add_option("--out", options->outDir, "directory for the CSVs and tables")->capture_default_str();
  command->add_flag("--quick", options->quick, "small grids and short runs (what CI runs)");
  command->add_option("--integrator", options->integrators,
                      "restrict to these integrators (repeatable; default: every one)")
      ->check(options::integratorName());
  command->add_option("--jobs", options->jobs, "threads for independent runs (results identical for any N)")
      ->capture_default_str()
      ->check(options::decimalInteger(1, 256));
  command->add_option("--max-stretch", options->criterion.maxRelativeConstraintError,
                      "failure threshold on the relative constraint error max |C|/r")
      ->capture_default_str()
      ->check(options::numberInRange(1e-6, 10.0));
  command->add_option("--energy-rise", options->criterion.energyRiseFraction,
                      "failure threshold on E(t) - E(0), as a fraction of the scene's releasable energy")
      ->capture_default_str()
      ->check(options::numberInRange(1e-6, 1e3));
  command->add_option("--shard", options->shard,
                      "K/N: run only shard K of N of the sweep's cells (index % N == K-1) into --out; "
                      "particle-lab merge combines the N shards");
  return options;
}

// The experiment's options as parsed, without those that do not change its
// results (--shard, --out, --jobs): what a shard's manifest records and a
// merge runs again. Flags by name, every value of an option after its name,
// in the order the options are declared.
std::vector<std::string> resultArguments(const CLI::App* command) {
  std::vector<std::string> kept{command->get_name()};
  for (const CLI::Option* option : command->get_options()) {
    const std::string name = option->get_name();
    if (option->count() == 0 || name == "--shard" || name == "--out" || name == "--jobs") continue;
    if (option->get_expected_max() == 0) {
      kept.push_back(name);
      continue;
    }
    for (const std::string& value : option->results()) kept.insert(kept.end(), {name, value});
  }
  return kept;
}

// Runs an experiment: all its cells, a shard of them (--shard), or the cells a
// merge replays. Ctrl-C stops it early, keeping the rows already written.
int experiment(const CLI::App* command, ExperimentOptions& options, const Context& context,
               const std::function<int()>& run) {
  std::optional<lab::ShardSpec> shard;
  if (!options.shard.empty()) shard = lab::parseShard(options.shard);
  lab::installInterruptHandler();
  try {
    if (context.replay) {
      if (shard) throw UsageError("merge: the shards' arguments hold --shard");
      options.cells = context.replay;
    } else if (shard) {
      options.cells = std::make_shared<lab::Cells>(*shard, options.outDir);
    }
    const int code = run();
    if (code == 0) options.cells->writeManifest(command->get_name(), resultArguments(command));
    return code;
  } catch (const output::WriteError&) {
    throw;  // exit 4, not a bad option
  } catch (const std::runtime_error& e) {  // an output file that cannot be written
    throw UsageError(e.what());
  }
}

// std::cout discards what is written to it while this lives (a merge's first
// replay): the stream stays good, so the command's result is not taken for
// a failed write of standard output.
class SilencedStdout {
 public:
  SilencedStdout() : kept_(std::cout.rdbuf(&discard_)) {}
  ~SilencedStdout() { std::cout.rdbuf(kept_); }
  SilencedStdout(const SilencedStdout&) = delete;
  SilencedStdout& operator=(const SilencedStdout&) = delete;

 private:
  struct Discard : std::streambuf {
    int overflow(int c) override { return traits_type::not_eof(c); }
    std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
  };
  Discard discard_;
  std::streambuf* kept_;
};

// An experiment is a subcommand taking --shard (addLabOptions).
bool isExperiment(const CLI::App& app, const std::string& name) {
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    if (sub->get_name() == name) return sub->get_option_no_throw("--shard") != nullptr;
  return false;
}

}  // namespace

Command addStabilityCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "stability", "largest surviving dt per integrator and chain length (stability map); the seed's Tables 1 and 2");
  auto options = addLabOptions(command);
  auto stability = std::make_shared<lab::StabilityOptions>();
  command->add_option("--duration", stability->duration,
                      "T of Tables 1 and 2: simulated seconds a run must survive")
      ->capture_default_str()
      ->check(options::numberInRange(lab::StabilityOptions::minDuration, lab::StabilityOptions::maxDuration));
  command->add_option("--failure-bound", stability->failureBound,
                      "Table 2: run enough starts per grid dt that the runs of the decade below each step, none "
                      "failing, bound the per-run failure probability by this at 95% confidence (default: the "
                      "plan's starts, and the bound they reach)")
      ->check(options::numberInRange(lab::StabilityOptions::minFailureBound, lab::StabilityOptions::maxFailureBound));
  return {command, [=](const Context& context) {
            return experiment(command, *options, context, [&] { return lab::runStability(*options, *stability); });
          }};
}

Command addTimingCommand(CLI::App& app) {
  auto* command = app.add_subcommand("timing", "cost per step against chain length and cloth size; the seed's Table 3");
  auto options = addLabOptions(command);
  auto timing = std::make_shared<lab::TimingOptions>();
  command->add_option("--repeats", timing->repeats, "timed repeats; the median is reported")
      ->capture_default_str()
      ->check(options::decimalInteger(1, 1000000));
  command->add_option("--steps", timing->steps, "steps per timed repeat")
      ->capture_default_str()
      ->check(options::decimalInteger(1, 1000000000));
  return {command, [=](const Context& context) {
            return experiment(command, *options, context, [&] { return lab::runTiming(*options, *timing); });
          }};
}

Command addAccuracyCommand(CLI::App& app) {
  auto* command = app.add_subcommand("accuracy", "work-precision: error at T against CPU time, per integrator and dt");
  auto options = addLabOptions(command);
  return {command, [=](const Context& context) {
            return experiment(command, *options, context, [&] { return lab::runAccuracy(*options); });
          }};
}

Command addExtremesCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "extremes", "stiff springs, mass ratios, feedback gains, CG budget, rod forms, the taut chain");
  auto options = addLabOptions(command);
  return {command, [=](const Context& context) {
            return experiment(command, *options, context, [&] { return lab::runExtremes(*options); });
          }};
}

Command addClaimsCommand(CLI::App& app) {
  auto* command = app.add_subcommand("claims", "the seed report's claims, each confirmed or refuted by a measurement");
  auto options = addLabOptions(command);
  return {command, [=](const Context& context) {
            return experiment(command, *options, context, [&] { return lab::runClaims(*options); });
          }};
}

Command addCostCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "cost", "the cost of accuracy: cheapest safe integrator and dt per scene and error budget");
  auto options = addLabOptions(command);
  return {command, [=](const Context& context) {
            return experiment(command, *options, context, [&] { return lab::runCost(*options); });
          }};
}

Command addLongtimeCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "longtime", "energy over 500 s per integrator (pendulum, 6-chain); implicit Euler's loss per period");
  auto options = addLabOptions(command);
  return {command, [=](const Context& context) {
            return experiment(command, *options, context, [&] { return lab::runLongtime(*options); });
          }};
}

Command addSmallStepsCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "small-steps", "XPBD substeps against iterations and against implicit Euler and RK4; the stiff cloth at 60 Hz");
  auto options = addLabOptions(command);
  return {command, [=](const Context& context) {
            return experiment(command, *options, context, [&] { return lab::runSmallSteps(*options); });
          }};
}

Command addRenderReportCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "render-report", "fill a Markdown template with the tables and values the experiments wrote");
  auto render = std::make_shared<lab::RenderOptions>();
  command->add_option("--template", render->templatePath, "template file")->required()->check(options::regularFile());
  command->add_option("--data", render->dataDir, "directory the experiments wrote")
      ->required()
      ->check(CLI::ExistingDirectory);
  command->add_option("--out", render->outPath, "rendered Markdown file")->required();
  command->add_option("--section", render->section,
                      "replace only the lines between this section's markers in --out (<!-- begin NAME: ... --> and "
                      "<!-- end NAME -->), keeping the rest");
  command->add_flag("--check", render->check,
                    "write nothing: exit 0 if --out already holds the rendering, 1 (naming the first differing line) if not");
  return {command, [=](const Context&) {
            lab::installInterruptHandler();
            try {
              return lab::renderReport(*render);
            } catch (const output::WriteError&) {
              throw;
            } catch (const std::runtime_error& e) {
              throw UsageError(e.what());
            }
          }};
}

Command addMergeCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "merge", "combine the shards of one experiment (--shard K/N) into the files an unsharded run writes");
  auto dirs = std::make_shared<std::vector<std::string>>();
  auto out = std::make_shared<std::string>();
  command->add_option("dirs", *dirs, "the shards' output directories")->required();
  command->add_option("--out", *out, "directory for the merged CSVs, tables and values")->required();
  return {command, [=](const Context&) {
            const lab::ShardSet set = lab::readShards(*dirs);
            // Only an experiment is run again (a command taking --shard), never
            // merge itself or another tool named by an edited manifest.
            if (!isExperiment(*command->get_parent(), set.experiment))
              throw UsageError("merge: the shards' manifest names '" + set.experiment +
                               "', which is not an experiment (made by a different run or version)");
            std::vector<std::string> arguments = set.arguments;
            arguments.insert(arguments.end(), {"--out", *out});
            // The experiment runs again with its own arguments, every cell
            // read from the shards: tables and derived numbers from all cells.
            // First with its outputs held back (and its standard output
            // silenced), so that every cell reads back before any file is
            // written; then again, writing.
            const auto replay = [&](bool writeOutputs) {
              Context context;
              context.replay = std::make_shared<lab::Cells>(set.cells, set.shardNames, writeOutputs);
              const int code = runCommandLine(arguments, context);
              const std::size_t enumerated = context.replay->count();
              if (code == 0 && enumerated != set.cellCount)
                throw UsageError("merge: the shards hold " + std::to_string(set.cellCount) +
                                 " cells, the experiment has " + std::to_string(enumerated) +
                                 " (made by a different version?)");
              return code;
            };
            int code = 0;
            {
              const SilencedStdout silenced;
              code = replay(false);
            }
            if (code == 0) code = replay(true);
            if (code == 0)
              std::fprintf(stderr, "[%s] merged %zu cells from %zu shards into '%s'\n", set.experiment.c_str(),
                           set.cellCount, set.shardNames.size(), output::printable(*out).c_str());
            return code;
          }};
}

}  // namespace cli
