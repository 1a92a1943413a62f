// particle-lab run: steps a scene without a window, with per-step diagnostics.
#include <iostream>
#include <memory>

#include "particles/tearing.h"
#include "particles/threads.h"
#include "cli/command.h"
#include "cli/run_loop.h"
#include "cli/run_progress.h"
#include "cli/step_output.h"
#include "join_names.h"
#include "lab/lab.h"
#include "options/option_checks.h"
#include "options/scene_source.h"
#include "options/thread_option.h"
#include "output/output_file.h"
#include "particles/check.h"
#include "particles/integrator.h"
#include "particles/particle_system.h"
#include "output/printable.h"
#include "output/format_number.h"

namespace cli {

namespace {

// At most 10^12 steps: beyond any run that could end, and far from overflow.
constexpr long long kMaxSteps = 1000000000000LL;

struct RunOptions {
  options::SceneSource source;
  std::string integrator;  // empty: the scene's own
  // --tolerance, --substeps, --iterations, --lines: each given one overrides the scene's.
  particles::IntegratorSettings integratorSettings;
  CLI::Option* toleranceOption = nullptr;
  CLI::Option* substepsOption = nullptr;
  CLI::Option* iterationsOption = nullptr;
  CLI::Option* linesOption = nullptr;
  double dt = 0.0;
  CLI::Option* dtOption = nullptr;  // not given: the scene's own dt
  long long steps = 0;
  std::string csvPath, trajectoryPath;
  long long every = 1;
  long long diagnosticsEvery = 1;
  int threads = particles::affinityCpuCount();
};

// A CSV file with its header written (numbers in their shortest exact form), or none when path is empty.
std::unique_ptr<output::CsvWriter> openOutput(const std::string& path, const char* option,
                                              const std::vector<std::string>& columns) {
  if (path.empty()) return nullptr;
  return std::make_unique<output::CsvWriter>(path, option, columns);
}

// --csv and --trajectory, opened; both on standard output would interleave two tables.
struct Outputs {
  std::unique_ptr<output::CsvWriter> csv, trajectory;
};
Outputs openOutputs(const RunOptions& o) {
  if (o.csvPath == "-" && o.trajectoryPath == "-")
    throw std::invalid_argument("--csv and --trajectory cannot both write to standard output ('-'); "
                                "give one of them a file name");
  Outputs out;
  out.csv = openOutput(o.csvPath, "--csv", kDiagnosticsColumns);
  out.trajectory = openOutput(o.trajectoryPath, "--trajectory", kTrajectoryColumns);
  return out;
}

// The scene's integrator and settings, with those the command line gives instead.
std::unique_ptr<particles::Integrator> chosenIntegrator(const RunOptions& o, const scenes::Scene& scene) {
  const std::string integratorName = o.integrator.empty() ? scene.integrator : o.integrator;
  particles::IntegratorSettings settings = scene.integratorSettings;
  if (o.toleranceOption->count()) settings.dopri5.tolerance = o.integratorSettings.dopri5.tolerance;
  if (o.substepsOption->count()) settings.xpbd.substeps = o.integratorSettings.xpbd.substeps;
  if (o.iterationsOption->count()) settings.xpbd.iterations = o.integratorSettings.xpbd.iterations;
  if (o.linesOption->count()) settings.xpbd.lines = o.integratorSettings.xpbd.lines;
  return particles::makeIntegrator(integratorName, settings);
}

// The line a finished run prints on standard output.
void printSummary(const scenes::Scene& scene, const particles::Integrator& integrator, double dt, long long steps,
                  double seconds) {
  const particles::ParticleSystem& s = *scene.system;
  std::cout << output::printable(scene.name) << " with " << integrator.name() << " at dt " << dt << ": "
            << output::plural(steps, "step") << " to t = " << s.time() << " in " << seconds << " s of simulation ("
            << (seconds > 0.0 ? steps / seconds : 0.0) << " steps/s); total energy " << s.totalEnergy()
            << ", max |C| " << s.maxConstraintError();
  if (s.tearing().on())
    std::cout << ", " << output::plural(static_cast<long long>(s.brokenLinks().size()), "link") << " torn";
  std::cout << '\n';
}

// The thread count asked for, lowered to the CPUs this process may run on
// (with a note on stderr).
void useThreads(int asked) {
  std::string note;
  particles::setThreadCount(options::threadsWithinAffinity(asked, note));
  if (!note.empty()) std::cerr << "particle-lab: note: " << note << '\n';
}

// The divergence bound's scale (sceneLength), refused when it overflows.
double boundedSceneLength(const RunOptions& o, const scenes::Scene& scene) {
  const double length = sceneLength(scene);
  if (!std::isfinite(length))
    throw std::invalid_argument(o.source.describe() +
                                ": its particles and view span more than a double holds (their extent overflows); "
                                "bring them nearer the origin");
  return length;
}

int run(const RunOptions& o) {
  // From here SIGINT, SIGTERM and SIGHUP only set a flag: reading a large
  // scene file stops (particles::Cancelled, exit 130), and the loop below
  // stops at the next step boundary with the files closed on complete rows.
  lab::installInterruptHandler();
  // Check every input before the first output.
  useThreads(o.threads);
  scenes::Scene scene = o.source.load();
  const std::unique_ptr<particles::Integrator> integrator = chosenIntegrator(o, scene);
  const double dt = o.dtOption->count() ? o.dt : scene.dt;  // both checked > 0 as read
  const double length = boundedSceneLength(o, scene);
  const Outputs out = openOutputs(o);
  output::CsvWriter* const csv = out.csv.get();
  output::CsvWriter* const trajectory = out.trajectory.get();

  particles::ParticleSystem& s = *scene.system;
  RunLoop loop(s, *integrator, dt, {csv, trajectory, o.every, o.diagnosticsEvery}, length);
  const auto diverge = [&](long long step, const std::string& reason) {
    std::cerr << "particle-lab: diverged at step " << step << " (t = " << s.time() << "): " << reason << '\n';
  };
  // Closes the outputs (a failed write or close throws WriteError) and returns code.
  const auto finish = [&](int code) {
    if (csv) csv->close();
    if (trajectory) trajectory->close();
    return code;
  };
  if (const std::string reason = loop.start(); !reason.empty()) {
    diverge(0, reason);
    return finish(kDiverged);
  }
  long long done = 0;
  double doneTime = s.time();
  RunProgress progress(o.steps, RunProgress::stderrIsTerminal());
  for (long long step = 1; step <= o.steps && !lab::interrupted(); ++step) {
    if (const std::string reason = loop.step(); !reason.empty()) {
      progress.erase();
      diverge(step, reason);
      return finish(kDiverged);
    }
    if (loop.cancelledStep()) break;
    if (const std::string notice = loop.takeNotice(); !notice.empty()) {
      progress.erase();
      std::cerr << "particle-lab: note: " << notice << '\n';
    }
    done = step;
    doneTime = s.time();
    progress.update(step, doneTime);
  }
  progress.erase();
  if (lab::interrupted()) {
    std::cerr << "particle-lab: interrupted after step " << done << " (t = " << doneTime
              << "): the output files hold every step up to it\n";
    return finish(kInterrupted);
  }
  finish(kSuccess);
  printSummary(scene, *integrator, dt, o.steps, loop.simulatedSeconds());
  return kSuccess;
}

}  // namespace

namespace {

// "in [1, 100000]": a setting's declared range, as the help states it.
std::string inRange(particles::IntRange range) {
  return "in [" + std::to_string(range.min) + ", " + std::to_string(range.max) + "]";
}

// The options that choose the integrator and its settings, dt and the step count.
void addSteppingOptions(CLI::App* sub, const std::shared_ptr<RunOptions>& options) {
  using particles::XpbdSettings;
  sub->add_option("--integrator", options->integrator,
                  "integrator: " + particles::integratorNames() + " (default: the scene's, rk4 for built-ins)")
      ->check(options::integratorName());
  options->toleranceOption =
      sub->add_option("--tolerance", options->integratorSettings.dopri5.tolerance,
                      "local error tolerance of the adaptive scheme (dopri5), >= " +
                          output::formatNumber(particles::Dopri5Settings::minTolerance) +
                          "; ignored by fixed-step integrators (default: the scene's, " +
                          output::formatNumber(particles::IntegratorSettings{}.dopri5.tolerance) + ")")
          ->check(options::integratorTolerance());
  options->substepsOption =
      sub->add_option("--substeps", options->integratorSettings.xpbd.substeps,
                      "xpbd: substeps per step, " + inRange(XpbdSettings::substepRange) +
                          " (ignored by the others; default: the scene's, " + std::to_string(XpbdSettings{}.substeps) +
                          ")")
          ->check(options::decimalInteger(XpbdSettings::substepRange.min, XpbdSettings::substepRange.max));
  options->iterationsOption =
      sub->add_option("--iterations", options->integratorSettings.xpbd.iterations,
                      "xpbd: constraint passes per substep, " + inRange(XpbdSettings::iterationRange) +
                          " (default: the scene's, " + std::to_string(XpbdSettings{}.iterations) + ")")
          ->check(options::decimalInteger(XpbdSettings::iterationRange.min, XpbdSettings::iterationRange.max));
  options->linesOption = sub->add_flag("--lines,!--no-lines", options->integratorSettings.xpbd.lines,
                                       "xpbd: solve each straight line of springs hanging from a held particle "
                                       "directly before the Gauss-Seidel pass (default: the scene's, off)");
  options->dtOption = sub->add_option("--dt", options->dt, "time step, simulated seconds, > 0 (default: the scene's)")
                          ->check(options::positiveNumber());
  sub->add_option("--steps", options->steps, "number of steps, a decimal integer >= 0")
      ->required()
      ->check(options::decimalInteger(0, kMaxSteps));
}

// The output files, how often they are written, and the thread count.
void addOutputOptions(CLI::App* sub, const std::shared_ptr<RunOptions>& options) {
  sub->add_option("--csv", options->csvPath,
                  "write one row per step (row 0: the initial state): step,t,kinetic,potential,total_energy,"
                  "max_constraint_error,cg_iterations,cg_residual,solves,force_evaluations,internal_steps,step_us,threads,contacts,sleeping "
                  "(cg_iterations: summed over every solve of the step; cg_residual: the largest relative "
                  "residual of them; solves: linear solves; force_evaluations: evaluations of every force; "
                  "internal_steps: accepted steps of an adaptive scheme, 1 otherwise; step_us: wall time of "
                  "the step's simulation, output excluded; threads: the threads the step ran on, at most "
                  "--threads; contacts: contacts the step resolved; sleeping: particles asleep at its end)")
      ->check(options::outputPath());
  sub->add_option("--trajectory", options->trajectoryPath,
                  "write step,t,particle,x,y,vx,vy for every particle every --every steps (and at step 0)")
      ->check(options::outputPath());
  sub->add_option("--every", options->every, "trajectory interval in steps, a decimal integer >= 1")
      ->capture_default_str()
      ->check(options::decimalInteger(1, kMaxSteps));
  options::addThreadsOption(*sub, options->threads);
  sub->add_option("--diagnostics-every", options->diagnosticsEvery,
                  "measure the diagnostics (energies, constraint error), check divergence and write the --csv "
                  "row every K steps (and at step 0); a divergence is then found up to K-1 steps late; a "
                  "decimal integer >= 1")
      ->capture_default_str()
      ->check(options::decimalInteger(1, kMaxSteps));
}

}  // namespace

Command addRunCommand(CLI::App& app) {
  auto options = std::make_shared<RunOptions>();
  CLI::App* sub = app.add_subcommand("run", "step a scene without a window and write per-step diagnostics");
  options->source.addOptions(*sub);
  addSteppingOptions(sub, options);
  addOutputOptions(sub, options);
  sub->footer(
      "Prints a summary (steps per second of simulation, final energy and constraint error, and the links torn\n"
      "when the scene tears) on stdout.\n"
      "On a terminal, a run that takes over a second shows a progress line on stderr, erased at the end.\n"
      "Exit codes: 0 done; 2 bad option value or scene file (one line on stderr); 3 the state became\n"
      "non-finite (|q|^2 or |v|^2 overflows), the total energy rose above E0 + 100 E_ref (the scene's\n"
      "energies and the work of its starting forces across its view: particles/divergence.h), a step\n"
      "failed (a solve with non-finite multipliers, an adaptive step below its floor or over its work\n"
      "cap, a particle over the contact work cap of 100000 impacts in one step), a constraint solve left\n"
      "a relative residual above 10, or a diagnostic is not finite: the run stops,\n"
      "stderr names the step, time and reason, and the CSV holds every step before it (finite numbers\n"
      "only); 4 an output file or stdout could not be written (disk full); 130 SIGINT, SIGTERM or SIGHUP: the run stops at\n"
      "a step boundary (a long step is cut short and not written) and the files hold complete rows; while the scene\n"
      "file is read, nothing is written. An output file is locked while it is written:\n"
      "a second run given the same path is refused (exit 2).");
  return {sub, [options](const Context&) { return run(*options); }};
}

}  // namespace cli
