// Registers the experiment subcommands with the `particle-lab` command line.
#include <iostream>

#include <CLI/CLI.hpp>

#include "lab/experiments.h"
#include "lab/render.h"

namespace lab {

namespace {

// Runs an experiment, turning its exceptions into one line and exit code 2.
int guarded(const std::function<int()>& run) {
  installInterruptHandler();
  try {
    return run();
  } catch (const std::exception& e) {
    std::cerr << "particle-lab: " << e.what() << '\n';
    return 2;
  }
}

void addCommonOptions(CLI::App* command, LabOptions& options) {
  command->add_option("--out", options.outDir, "directory for the CSVs and tables")->capture_default_str();
  command->add_flag("--quick", options.quick, "small grids and short runs (for CI)");
  command->add_option("--integrator", options.integrators,
                      "restrict to these integrators (repeatable; default: all)");
}

// Option values bound by CLI11, kept alive by the callbacks that read them.
struct CommandState {
  LabOptions options;
  StabilityOptions stability;
  TimingOptions timing;
  RenderOptions render;
};

// Exits the program with the experiment's code once CLI11 has parsed.
void finish(int code) {
  std::cout << std::flush;
  std::exit(code);
}

}  // namespace

void registerLabCommands(CLI::App& app) {
  auto state = std::make_shared<CommandState>();
  LabOptions& options = state->options;
  StabilityOptions& stability = state->stability;
  TimingOptions& timing = state->timing;
  RenderOptions& render = state->render;

  auto* stab = app.add_subcommand("stability", "stability map: largest surviving dt per chain length and integrator; Tables 1 and 2");
  addCommonOptions(stab, options);
  stab->add_option("--duration", stability.duration, "simulated seconds a run must survive (T)")
      ->capture_default_str()->check(CLI::PositiveNumber);
  stab->add_option("--max-stretch", stability.explosion.maxRelativeStretch,
                   "explosion threshold on max |C|/r")->capture_default_str()->check(CLI::PositiveNumber);
  stab->callback([state] { finish(guarded([&] { return runStability(state->options, state->stability); })); });

  auto* time = app.add_subcommand("timing", "cost per step against chain length and cloth size; Table 3");
  addCommonOptions(time, options);
  time->add_option("--repeats", timing.repeats, "timed repeats (median reported)")
      ->capture_default_str()->check(CLI::PositiveNumber);
  time->add_option("--steps", timing.steps, "steps per repeat")->capture_default_str()->check(CLI::PositiveNumber);
  time->callback([state] { finish(guarded([&] { return runTiming(state->options, state->timing); })); });

  auto* acc = app.add_subcommand("accuracy", "work-precision: error at T against cost, per integrator and dt");
  addCommonOptions(acc, options);
  acc->callback([state] { finish(guarded([&] { return runAccuracy(state->options); })); });

  auto* ext = app.add_subcommand("extremes", "stiffness, mass ratio, feedback gains, CG budget, rod forms, taut chain");
  addCommonOptions(ext, options);
  ext->callback([state] { finish(guarded([&] { return runExtremes(state->options); })); });

  auto* cl = app.add_subcommand("claims", "the seed report's claims, each measured");
  addCommonOptions(cl, options);
  cl->callback([state] { finish(guarded([&] { return runClaims(state->options); })); });

  auto* rep = app.add_subcommand("render-report", "fill a Markdown template with the tables and values the experiments wrote");
  rep->add_option("--template", render.templatePath, "template file")->required()->check(CLI::ExistingFile);
  rep->add_option("--data", render.dataDir, "directory the experiments wrote")->required()->check(CLI::ExistingDirectory);
  rep->add_option("--out", render.outPath, "rendered Markdown")->required();
  rep->callback([state] { finish(guarded([&] { return renderReport(state->render); })); });
}

}  // namespace lab
