// The laboratory's subcommands: stability, timing, accuracy, extremes, claims,
// and render-report, which fills the report template from their output.
#include <memory>

#include "cli/command.h"
#include "lab/experiments.h"
#include "lab/render.h"
#include "options/option_checks.h"
#include "output_file.h"
#include "particles/check.h"

namespace cli {

namespace {

// Options every experiment takes; held by the returned action.
std::shared_ptr<lab::LabOptions> addLabOptions(CLI::App* command) {
  auto options = std::make_shared<lab::LabOptions>();
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
      ->capture_default_str();
  command->add_option("--energy-rise", options->criterion.energyRiseFraction,
                      "failure threshold on E(t) - E(0), as a fraction of the scene's releasable energy")
      ->capture_default_str();
  return options;
}

// Ranges of the options every experiment takes (one line and exit 2 outside
// them; --jobs is checked as it is read).
void validate(const lab::LabOptions& options) {
  particles::requireInRange("--max-stretch", options.criterion.maxRelativeConstraintError, 1e-6, 10.0);
  particles::requireInRange("--energy-rise", options.criterion.energyRiseFraction, 1e-6, 1e3);
}

// Runs an experiment: Ctrl-C stops it early, keeping the rows already written.
int experiment(const std::function<int()>& run) {
  lab::installInterruptHandler();
  try {
    return run();
  } catch (const scenes::WriteError&) {
    throw;  // exit 4, not a bad option
  } catch (const std::runtime_error& e) {  // an output file that cannot be written
    throw UsageError(e.what());
  }
}

}  // namespace

Command addStabilityCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "stability", "largest surviving dt per integrator and chain length (stability map); the seed's Tables 1 and 2");
  auto options = addLabOptions(command);
  auto stability = std::make_shared<lab::StabilityOptions>();
  command->add_option("--duration", stability->duration,
                      "T of Tables 1 and 2: simulated seconds a run must survive")
      ->capture_default_str();
  return {command, [=] {
            validate(*options);
            particles::requireInRange("--duration", stability->duration, lab::StabilityOptions::minDuration,
                                      lab::StabilityOptions::maxDuration);
            return experiment([&] { return lab::runStability(*options, *stability); });
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
  return {command, [=] {
            validate(*options);
            return experiment([&] { return lab::runTiming(*options, *timing); });
          }};
}

Command addAccuracyCommand(CLI::App& app) {
  auto* command = app.add_subcommand("accuracy", "work-precision: error at T against CPU time, per integrator and dt");
  auto options = addLabOptions(command);
  return {command, [=] {
            validate(*options);
            return experiment([&] { return lab::runAccuracy(*options); });
          }};
}

Command addExtremesCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "extremes", "stiff springs, mass ratios, feedback gains, CG budget, rod forms, the taut chain");
  auto options = addLabOptions(command);
  return {command, [=] {
            validate(*options);
            return experiment([&] { return lab::runExtremes(*options); });
          }};
}

Command addClaimsCommand(CLI::App& app) {
  auto* command = app.add_subcommand("claims", "the seed report's claims, each confirmed or refuted by a measurement");
  auto options = addLabOptions(command);
  return {command, [=] {
            validate(*options);
            return experiment([&] { return lab::runClaims(*options); });
          }};
}

Command addCostCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "cost", "the cost of accuracy: cheapest safe integrator and dt per scene and error budget");
  auto options = addLabOptions(command);
  return {command, [=] { return experiment([&] { return lab::runCost(*options); }); }};
}

Command addLongtimeCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "longtime", "energy over 500 s per integrator (pendulum, 6-chain); implicit Euler's loss per period");
  auto options = addLabOptions(command);
  return {command, [=] { return experiment([&] { return lab::runLongtime(*options); }); }};
}

Command addSmallStepsCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "small-steps", "XPBD substeps against iterations and against implicit Euler and RK4; the stiff cloth at 60 Hz");
  auto options = addLabOptions(command);
  return {command, [=] { return experiment([&] { return lab::runSmallSteps(*options); }); }};
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
  return {command, [=] { return experiment([&] { return lab::renderReport(*render); }); }};
}

}  // namespace cli
