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
  double failureBound = 0.0;  // 0: certifyStarts per grid point of a margin
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

// One line of the table: columns padded to their widths.
std::string columns(const std::vector<std::pair<std::string, int>>& cells) {
  std::string line;
  for (const auto& [text, width] : cells) {
    line += text;
    // Pad by characters, not bytes: "–" is one column wide.
    int shown = 0;
    for (unsigned char c : text) shown += (c & 0xC0) != 0x80;
    line += std::string(std::max(1, width - shown), ' ');
  }
  while (!line.empty() && line.back() == ' ') line.pop_back();
  return line;
}

// "12%" of the budget left, flagged when it is thin (lab::thinHeadroom).
std::string headroomText(const lab::Pick& p, double error) {
  const double left = lab::headroom(p, error);
  return output::formatFixed(100.0 * left, 0) + "%" + (lab::thinHeadroom(p, error) ? " !" : "");
}

// The certified margin and the bound its runs support: "0.00025-0.00039, p ≤ 0.0067".
std::string marginText(const lab::Pick& p) {
  if (!p.certified()) return "–";
  return cell(p.certifiedLo) + "-" + cell(p.certifiedHi) + ", " + lab::boundText(p.marginRuns);
}

// The table: one line per integrator, its pick or why it has none.
void printPicks(const lab::Survey& survey, const std::vector<lab::Pick>& picks, const std::string& budgetsText,
                double error) {
  std::cout << columns({{"integrator", 18}, {"dt", 12}, {"tolerance", 11}, {"max error", 11}, {"headroom", 10},
                        {"energy err", 11}, {"|C|/r", 10}, {"surviving dt", 13}, {"CPU s per sim s (min-max)", 28},
                        {"certified margin, failure bound", 0}})
            << "\n";
  for (std::size_t k = 0; k < picks.size(); ++k) {
    const auto& scan = survey.integrators[k];
    const auto& p = picks[k];
    const std::string safe = scan.adaptive ? "–" : cell(scan.safeDt) + (scan.safeAtTop ? "+" : "");
    std::string line;
    if (!scan.refused.empty())
      line = columns({{scan.integrator, 18}}) + " refuses the scene: " + scan.refused.substr(0, 180);
    else if (p.found)
      line = columns({{scan.integrator, 18}, {cell(p.candidate.dt), 12},
                      {scan.adaptive ? cell(p.candidate.tolerance) : "–", 11}, {cell(p.error()), 11},
                      {headroomText(p, error), 10}, {cell(p.candidate.energyError), 11},
                      {cell(p.candidate.constraintDrift), 10}, {safe, 13},
                      {cell(p.cpuPerSimulatedSecond) + " (" + cell(p.cpuMin) + "-" + cell(p.cpuMax) + ")", 28},
                      {marginText(p) + (p.tie ? "  (tie)" : ""), 0}});
    else if (!p.uncertified.empty())
      line = columns({{scan.integrator, 18}}) + " none certified: " + p.uncertified.substr(0, 200);
    else
      line = columns({{scan.integrator, 18}}) + " none within " + budgetsText + " on the scanned grid (" +
             output::plural(static_cast<long long>(scan.scanned.size()), "run") + "), surviving dt " + safe;
    std::cout << line << "\n";
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
  settings.failureBound = o.failureBound;
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

// The reference and what it met, before the table.
void printReference(const lab::Survey& survey) {
  std::cout << "reference: " << survey.reference << "\n";
  if (survey.touchedWall)
    std::cout << "contacts: the odeint reference met one (" << survey.contact << ")"
              << (survey.limit.empty() ? "; the reference is the self-converged run of a contact-aware scheme, "
                                         "and every error below is measured against it"
                                       : "")
              << "\n";
}

// What the margins and bounds of the table mean.
void printMarginNote(const lab::SurveySettings& settings, const std::string& budgets) {
  if (settings.certifyMembers <= 0) return;
  std::cout << "certified margin: every dt (adaptive: tolerance) " << lab::general(100.0 * settings.certifyResolution)
            << "% apart in it survives T within " << budgets << " on every start ("
            << (settings.failureBound > 0.0 ? "enough starts for a bound of " + lab::general(settings.failureBound)
                                            : output::plural(settings.certifyMembers, "start"))
            << ": as built and perturbed by 1e-6 of the scene's size); the failure bound p is the 95% upper bound on "
               "the per-run probability of a failure or a miss of E that the margin's runs support (none failed); "
               "max error is the largest over those starts at the pick's dt; headroom is 1 - max error / E, "
               "! when under "
            << lab::general(100.0 * lab::kThinHeadroom) << "%; a pick is at most " << lab::general(settings.safeFraction)
            << " of its margin's top; surviving dt: the survey's coarse scan (" << settings.members
            << " starts), not a safe step; "
            << (settings.certifyAll ? "every pick is certified"
                                    : "the cheapest pick and its ties are certified (--certify-all: every pick)")
            << "\n";
}

int advise(const AdviseOptions& o) {
  lab::installInterruptHandler();  // a signal while a large scene file is read stops it too
  o.source.load();  // bad scene input fails here, before any measurement
  const lab::SurveySettings settings = surveySettings(o);
  const lab::Advice advice = lab::advise([&] { return o.source.load(); }, settings);
  if (lab::interrupted() || !advice.complete) return 130;
  const lab::Survey& survey = advice.survey;
  const std::vector<lab::Pick>& picks = advice.picks;

  std::cout << "scene " << output::printable(survey.scene) << ", " << output::plural(survey.particles, "particle")
            << ", size " << lab::general(survey.size) << ", T = " << lab::general(o.horizon)
            << " s, E = " << lab::general(o.error) << budgetsLine(o) << "\n";
  printReference(survey);
  if (!survey.limit.empty()) {
    std::cout << "advise: " << survey.limit << "; the longest horizon it can certify: --horizon "
              << output::formatNumber(survey.certifiableHorizon) << "\n";
    return kCannotCertify;
  }
  printPicks(survey, picks, budgetsName(o), o.error);
  printMarginNote(settings, budgetsName(o));
  const int best = advice.best;
  if (best < 0) {
    std::cout << "advise: no integrator meets --error " << lab::general(o.error) << budgetsLine(o) << " over "
              << lab::general(o.horizon) << " s within its safe range\n";
    return 1;
  }
  const lab::Pick& chosen = picks[best];
  std::string ties;
  for (const lab::Pick& p : picks)
    if (p.tie) ties += (ties.empty() ? "" : ", ") + p.candidate.integrator;
  if (!ties.empty())
    std::cout << "advise: within the timing spread of " << chosen.candidate.integrator << " (a tie, "
              << output::plural(o.repeats, "interleaved repeat") << "): " << ties << "\n";
  const lab::TimingSpread spread = lab::timingSpread(picks, best);
  if (spread.ties > 0 && spread.spread > settings.noisySpread)
    std::cout << "advise: warning: the timings are noisy: the repeats of the tied picks spread up to "
              << output::formatFixed(spread.spread, 1) << "x (" << cell(spread.lo) << "-" << cell(spread.hi)
              << " CPU s per simulated s), so " << output::plural(spread.ties + 1, "pick")
              << " tie; run again on a quieter machine or with more --repeats\n";
  if (lab::thinHeadroom(chosen, o.error))
    std::cout << "advise: warning: the pick's error " << cell(chosen.error()) << " is within "
              << lab::general(100.0 * lab::kThinHeadroom) << "% of E: no headroom\n";
  std::cout << "advise: " << lab::pickArguments(chosen.candidate) << "\n";
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
  command->add_option("--failure-bound", options->failureBound,
                      "run enough starts at every dt of a pick's margin that its runs, none failing, bound the "
                      "per-run probability of a failure or a miss of E by this at 95% confidence (Clopper-Pearson; "
                      "at least --certify-starts)")
      ->check(options::numberInRange(1e-6, 0.5));
  command->add_flag("--certify-all", options->certifyAll,
                    "certify every integrator's pick, not only the cheapest and its ties");
  command->footer(
      "A scene whose odeint reference meets a contact (discs touching, a particle or edge reaching a collider) is\n"
      "measured against a reference by self-convergence of the contact-aware schemes: dt halved until two\n"
      "successive runs agree within E/10 over T; the table's first lines say which scheme, dt and observed order.\n"
      "Exit codes: 0 a pick (the last line gives it as run options); 1 no integrator meets the budgets within\n"
      "its safe range; 2 bad option value or scene file (one line on stderr); 5 no reference can certify E over\n"
      "T (the references part by more than E/10: chaos; or self-convergence with contacts not reached), with\n"
      "the longest horizon that can be certified; 130 interrupted.");
  return {command, [=](const Context&) { return advise(*options); }};
}

}  // namespace cli
