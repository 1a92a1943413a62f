// `particle-lab advise`: measures this scene and names the cheapest integrator
// and step whose maximum position error over [0, T] against a reference is at
// most E, and optionally whose energy error and constraint drift stay within
// their budgets (lab/advise.h). The table goes to stdout, progress to stderr; the last
// line is the advice as run options.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>

#include "cli/command.h"
#include "output/format_number.h"
#include "output/printable.h"
#include "lab/advise.h"
#include "options/option_checks.h"
#include "options/scene_source.h"
#include "particles/check.h"
#include "output/format_number.h"

namespace cli {

namespace {

struct AdviseOptions {
  options::SceneSource source;
  double error = 0.0;    // E, world units
  double energyBudget = std::numeric_limits<double>::infinity();  // of |E − E_ref| / E_s; infinite: none
  double driftBudget = std::numeric_limits<double>::infinity();   // of |C|/r; infinite: none
  double horizon = 0.0;  // T, simulated seconds
  std::vector<std::string> integrators;
  int repeats = 5;
  long maxSteps = 100000;
  double referenceTolerance = lab::SurveySettings{}.referenceTolerance;
  int certifyStarts = lab::SurveySettings{}.certifyMembers;
  bool certifyAll = false;
};

std::string cell(double value) { return std::isfinite(value) ? lab::general(value, 3) : "–"; }

// The optional budgets as given, ", energy error <= X, |C|/r <= Y" ("" when none is).
std::string budgetsLine(const AdviseOptions& o) {
  std::string text;
  if (std::isfinite(o.energyBudget)) text += ", energy error <= " + lab::general(o.energyBudget);
  if (std::isfinite(o.driftBudget)) text += ", |C|/r <= " + lab::general(o.driftBudget);
  return text;
}

// The table: one line per integrator, its pick or why it has none.
void printPicks(const lab::Survey& survey, const std::vector<lab::Pick>& picks, const std::string& budgetsText) {
  std::cout << "integrator        dt          tolerance  max error  energy err |C|/r       safe dt     CPU s per sim s "
               "(min-max)   certified margin\n";
  for (std::size_t k = 0; k < picks.size(); ++k) {
    const auto& scan = survey.integrators[k];
    const auto& p = picks[k];
    const std::string safe = scan.adaptive ? "–" : cell(scan.safeDt) + (scan.safeAtTop ? "+" : "");
    char line[256];
    if (!scan.refused.empty())
      std::snprintf(line, sizeof line, "%-17s refuses the scene: %.180s\n", scan.integrator.c_str(),
                    scan.refused.c_str());
    else if (p.found)
      std::snprintf(line, sizeof line, "%-17s %-11s %-10s %-10s %-10s %-10s %-11s %-27s %s%s\n",
                    scan.integrator.c_str(), cell(p.candidate.dt).c_str(),
                    scan.adaptive ? cell(p.candidate.tolerance).c_str() : "–", cell(p.candidate.maxError).c_str(),
                    cell(p.candidate.energyError).c_str(), cell(p.candidate.constraintDrift).c_str(), safe.c_str(),
                    (cell(p.cpuPerSimulatedSecond) + " (" + cell(p.cpuMin) + "-" + cell(p.cpuMax) + ")").c_str(),
                    p.certifiedHi > 0.0 ? (cell(p.certifiedLo) + "-" + cell(p.certifiedHi)).c_str() : "–",
                    p.tie ? "  (tie)" : "");
    else if (!p.uncertified.empty())
      std::snprintf(line, sizeof line, "%-17s none certified: %.200s\n", scan.integrator.c_str(),
                    p.uncertified.c_str());
    else
      std::snprintf(line, sizeof line, "%-17s none within %s on the scanned grid (%s), safe dt %s\n",
                    scan.integrator.c_str(), budgetsText.c_str(),
                    output::plural(static_cast<long long>(scan.scanned.size()), "run").c_str(), safe.c_str());
    std::cout << line;
  }
}

// The survey `advise` runs: the options' budgets and limits, progress on stderr.
lab::SurveySettings surveySettings(const AdviseOptions& o) {
  lab::SurveySettings settings;
  settings.horizon = o.horizon;
  settings.targetError = settings.abortError = o.error;
  settings.energyBudget = o.energyBudget;
  settings.driftBudget = o.driftBudget;
  settings.integrators = o.integrators;
  settings.repeats = o.repeats;
  settings.maxSteps = o.maxSteps;
  settings.referenceTolerance = o.referenceTolerance;
  settings.certifyMembers = o.certifyStarts;
  settings.certifyAll = o.certifyAll;
  auto lastReport = std::make_shared<double>(-1.0);
  settings.progress = [lastReport, horizon = o.horizon, repeats = o.repeats](double fraction) {
    if (fraction - *lastReport < 0.05 && fraction < 1.0) return;
    *lastReport = fraction;
    if (fraction == 0.0)
      std::fprintf(stderr, "advise: computing the reference over %g s\n", horizon);
    else
      std::fprintf(stderr, "advise: %3.0f%% done (the scan, then %s of each pick)\n", 100.0 * fraction,
                   output::plural(repeats, "timed repeat").c_str());
  };
  return settings;
}

// What the budgets are called in the table's lines: "E", or "the budgets" when there are more.
std::string budgetsName(const AdviseOptions& o) {
  return std::isfinite(o.energyBudget) || std::isfinite(o.driftBudget) ? "the budgets" : "E";
}

int advise(const AdviseOptions& o) {
  lab::installInterruptHandler();  // a signal while a large scene file is read stops it too
  o.source.load();  // bad scene input fails here, before any measurement
  const lab::SurveySettings settings = surveySettings(o);
  const lab::Advice advice = lab::advise([&] { return o.source.load(); }, settings);
  if (lab::interrupted() || !advice.complete) return 130;
  const lab::Survey& survey = advice.survey;
  const std::vector<lab::Pick>& picks = advice.picks;

  std::cout << "scene " << output::printable(survey.scene) << ", " << output::plural(survey.particles, "particle") << ", size "
            << lab::general(survey.size) << ", T = " << lab::general(o.horizon) << " s, E = " << lab::general(o.error)
            << budgetsLine(o) << "\nreference: " << survey.reference << (survey.touchedWall ? " [passes through a wall]" : "") << "\n";
  if (!survey.limit.empty()) {
    std::cout << "advise: " << survey.limit << "; the longest horizon it can certify: --horizon "
              << output::formatNumber(survey.certifiableHorizon) << "\n";
    return kCannotCertify;
  }
  printPicks(survey, picks, budgetsName(o));
  if (settings.certifyMembers > 0)
    std::cout << "certified margin: every dt (adaptive: tolerance) " << lab::general(100.0 * settings.certifyResolution)
              << "% apart in it survives T on " << output::plural(settings.certifyMembers, "start")
              << " (adaptive: within " << budgetsName(o) << " from the start as built); a pick is at most "
              << lab::general(settings.safeFraction) << " of its margin's top; "
              << (settings.certifyAll ? "every pick is certified" : "the cheapest pick and its ties are certified (--certify-all: every pick)")
              << "\n";
  const int best = advice.best;
  if (best < 0) {
    std::cout << "advise: no integrator meets --error " << lab::general(o.error) << budgetsLine(o) << " over "
              << lab::general(o.horizon) << " s within its safe range\n";
    return 1;
  }
  std::string ties;
  for (const lab::Pick& p : picks)
    if (p.tie) ties += (ties.empty() ? "" : ", ") + p.candidate.integrator;
  if (!ties.empty())
    std::cout << "advise: within the timing spread of " << picks[best].candidate.integrator << " (a tie, "
              << output::plural(o.repeats, "interleaved repeat") << "): " << ties << "\n";
  std::cout << "advise: " << lab::pickArguments(picks[best].candidate) << "\n";
  return kSuccess;
}

}  // namespace

Command addAdviseCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "advise", "measure the scene and name the cheapest integrator and dt within a position error over a horizon");
  auto options = std::make_shared<AdviseOptions>();
  options->source.addOptions(*command);
  command->add_option("--error", options->error, "E: largest particle position error allowed, world units")
      ->required()
      ->check(options::positiveNumber());
  command->add_option("--horizon", options->horizon, "T: simulated seconds the error is measured over")
      ->required()
      ->check(options::positiveNumber());
  command->add_option("--energy-error", options->energyBudget,
                      "largest energy error |E - E_ref| over the run, as a fraction of the releasable energy E_s "
                      "(default: none)")
      ->check(options::positiveNumber());
  command->add_option("--constraint-drift", options->driftBudget,
                      "largest constraint drift |C|/r over the run (default: none)")
      ->check(options::positiveNumber());
  command->add_option("--integrator", options->integrators,
                      "consider only these integrators (repeatable; default: every one)")
      ->check(options::integratorName());
  command->add_option("--repeats", options->repeats, "timed repeats of each pick; the median is reported")
      ->capture_default_str()
      ->check(options::decimalInteger(1, 1000000));
  command->add_option("--max-steps", options->maxSteps, "the smallest dt scanned is T / max-steps")
      ->capture_default_str()
      ->check(options::decimalInteger(1, 1000000000));
  command->add_option("--reference-tolerance", options->referenceTolerance,
                      "odeint's error tolerance per step for the reference (checked at 100x it), in [1e-13, 1]")
      ->capture_default_str()
      ->check(options::numberInRange(lab::kMinReferenceTolerance, 1.0));
  command->add_option("--certify-starts", options->certifyStarts,
                      "starts on which every dt of a pick's margin must survive (0: picks are not certified)")
      ->capture_default_str()
      ->check(options::decimalInteger(0, 1000));
  command->add_flag("--certify-all", options->certifyAll,
                    "certify every integrator's pick, not only the cheapest and its ties");
  return {command, [=](const Context&) { return advise(*options); }};
}

}  // namespace cli
