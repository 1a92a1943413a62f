// `particle-lab cost`: the cost of accuracy. For each scene and error budget
// (relative to the scene's size), the cheapest integrator and dt whose maximum
// particle position error over [0, T] against an independent reference meets
// the budget while dt ≤ 0.8 × that integrator's safe boundary on this scene,
// and its CPU time per simulated second (median of repeats, with the spread).
// Built on the advice core (lab/advise.h): one survey per scene serves every budget.
#include <cmath>

#include "lab/advise.h"
#include "lab/cells.h"
#include "lab/experiments.h"
#include "lab/lab_scene.h"
#include "lab/results.h"
#include "output/format_number.h"
#include "particles/integrator.h"

namespace lab {

namespace {

struct CostScene {
  std::string label;
  std::string scene;
  std::map<std::string, std::string> params;
  double horizon;   // T, simulated seconds
  long maxSteps;    // the grid's smallest dt is T / maxSteps
  bool closedForm;  // the oscillator: its closed form is the reference
};

// A budget is only measurable where the reference is much better than it.
constexpr double kReferenceMargin = 10.0;

// What the tables need of one integrator's scan.
struct ScanSummary {
  std::string integrator;
  bool adaptive = false;
  double safeDt = 0.0, firstFailureDt = 0.0;
  long runs = 0, ensembleRuns = 0;
};
template <class Io>
void fields(Io& io, ScanSummary& s) {
  io("integrator", s.integrator), io("adaptive", s.adaptive), io("safe_dt", s.safeDt);
  io("first_failure_dt", s.firstFailureDt), io("runs", s.runs), io("ensemble_runs", s.ensembleRuns);
}

// One scene's cell: its survey and the picks per budget (none where the
// reference is not converged enough to judge the budget).
struct Surveyed {
  int particles = 0;
  double size = 0.0, referenceAgreement = 0.0;
  std::vector<ScanSummary> integrators;
  std::vector<std::vector<Pick>> picks;  // per budget
};
template <class Io>
void fields(Io& io, Surveyed& s) {
  io("particles", s.particles), io("size", s.size), io("reference_agreement", s.referenceAgreement);
  io("integrators", s.integrators), io("picks", s.picks);
}

bool measurable(double budget, double referenceAgreement) { return !(budget < kReferenceMargin * referenceAgreement); }

// One scene at growing sizes: what the cheapest choice costs as the particle count grows.
struct SizeFamily {
  std::string name;  // "chain", "cloth"
  std::vector<CostScene> sizes;
};

// A scene with contacts, asked as a user asks `advise`: its demo defaults
// (not the seed's), an absolute budget E over T.
struct ContactQuestion {
  std::string label;
  std::string scene;
  std::map<std::string, std::string> params;
  double horizon;  // T, simulated seconds
  double error;    // E, world units
};

// What the experiment surveys.
struct CostPlan {
  std::vector<CostScene> scenes;
  std::vector<SizeFamily> families;
  int repeats = 0;  // timed repeats per pick; the median is reported
  std::vector<ContactQuestion> contacts;
  int contactStarts = 3;  // starts per grid point of a contact pick's margin (its runs are long)
};

// Error budgets, × the scene's size: of the scenes, and of the size families.
const std::vector<double> kBudgets = {1e-2, 1e-4, 1e-6};
const std::vector<double> kSizeBudgets = {1e-2, 1e-4};
constexpr double kSizeHorizon = 10.0;  // T of the size families, simulated seconds

CostScene chainOfLength(int length, double horizon, long maxSteps) {
  return {std::to_string(length) + "-chain", "test-chain", {{"cl", std::to_string(length)}}, horizon, maxSteps, false};
}
CostScene clothOfSide(int side, double horizon, long maxSteps) {
  const std::string n = std::to_string(side);
  return {n + "x" + n + " cloth", "cloth", {{"width", n}, {"height", n}}, horizon, maxSteps, false};
}

// Small scenes, short horizons: proves the code runs.
CostPlan quickPlan() {
  return {{{"oscillator", "oscillator", {}, 10.0, 2000, true},
           {"pendulum", "pendulum", {}, 20.0, 2000, false},
           {"6-chain", "test-chain", {{"cl", "6"}}, 5.0, 1000, false},
           {"6x6 cloth", "cloth", {{"width", "6"}, {"height", "6"}}, 2.0, 500, false},
           {"hair", "hair", {{"curls", "1"}, {"particles", "6"}}, 1.0, 1000, false}},
          {{"chain", {chainOfLength(3, 1.0, 500), chainOfLength(6, 1.0, 500)}},
           {"cloth", {clothOfSide(4, 1.0, 500), clothOfSide(6, 1.0, 500)}}},
          2,
          {{"small hair", "hair", {{"curls", "2"}, {"particles", "8"}}, 0.1, 1e-3}},
          2};
}

// The size families run over the first 10 s from release, not five periods:
// with the seed's weak gravity a shorter horizon leaves every size's pick at
// the top of the dt grid (at 2 s, all of them), so the budgets never bind; a
// longer one meets chaos (the 24-chain's references have parted by 60 s) and
// the largest cloth's survey would grow past the report's time.
CostPlan fullPlan() {
  std::vector<CostScene> chains, cloths;
  for (int length : {6, 12, 24, 48, 96, 240}) chains.push_back(chainOfLength(length, kSizeHorizon, 20000));
  for (int side : {8, 16, 32, 64}) cloths.push_back(clothOfSide(side, kSizeHorizon, 10000));
  return {{{"oscillator", "oscillator", {}, 32.0, 100000, true},
           {"pendulum", "pendulum", {}, 100.0, 100000, false},
           {"24-chain", "test-chain", {{"cl", "24"}}, 20.0, 20000, false},
           {"24-chain", "test-chain", {{"cl", "24"}}, 60.0, 20000, false},
           {"16x16 cloth", "cloth", {{"width", "16"}, {"height", "16"}}, 10.0, 10000, false},
           {"hair", "hair", {}, 10.0, 20000, false}},
          {{"chain", chains}, {"cloth", cloths}},
          SurveySettings{}.repeats,
          {{"hair", "hair", {}, 2.0, 1e-3},
           {"8-way cloth with its wall", "cloth", {{"links", "8"}}, 5.0, 1e-3},
           {"small hair (2 strands of 12)", "hair", {{"curls", "2"}, {"particles", "12"}}, 0.2, 1e-3}},
          3};
}

// One survey: runs stop once beyond the loosest budget, and each
// integrator's scan ends within the tightest.
SurveySettings surveySettings(const LabOptions& options, const CostPlan& plan, const CostScene& scene,
                              const std::vector<double>& budgets) {
  SurveySettings settings;
  settings.horizon = scene.horizon;
  settings.maxSteps = scene.maxSteps;
  settings.integrators = selectedIntegrators(options);
  settings.repeats = plan.repeats;
  settings.failure = options.criterion;
  settings.relativeToSize = true;
  settings.abortError = budgets.front();
  settings.targetError = budgets.back();
  return settings;
}

// One scene's survey and its picks per budget (nullopt: interrupted).
std::optional<Surveyed> surveyCostScene(const CostScene& scene, const SurveySettings& settings,
                                        const std::vector<double>& budgets) {
  const auto build = [&] { return buildLabScene(scene.scene, scene.params); };
  ClosedForm closedForm;
  if (scene.closedForm)
    closedForm = [&](double T, double h) { return oscillatorReference(scene.params, T, h, scenes::kSeedPreset); };
  const Survey survey = surveyScene(build, settings, closedForm);
  if (interrupted()) return std::nullopt;
  Surveyed out{survey.particles, survey.size, survey.referenceAgreement, {}, {}};
  for (const auto& scan : survey.integrators)
    out.integrators.push_back({scan.integrator, scan.adaptive, scan.safeDt, scan.firstFailureDt,
                               static_cast<long>(scan.scanned.size()), scan.ensembleRuns});
  for (double relative : budgets)
    out.picks.push_back(measurable(relative * survey.size, survey.referenceAgreement)
                            ? pickPerIntegrator(build, survey, settings, relative * survey.size)
                            : std::vector<Pick>{});
  if (interrupted()) return std::nullopt;
  return out;
}

void recordSettings(const LabOptions& options, const CostPlan& plan) {
  const SurveySettings defaults;
  recordValue(options, "cost.safe_fraction", general(defaults.safeFraction));
  recordValue(options, "cost.grid_ratio", fixed(std::pow(2.0, 1.0 / stepsPerOctave(defaults.gridResolution)), 3));
  recordValue(options, "cost.members", std::to_string(defaults.members));
  recordValue(options, "cost.certify_members", std::to_string(defaults.certifyMembers));
  recordValue(options, "cost.certify_resolution_percent", general(100.0 * defaults.certifyResolution));
  recordValue(options, "cost.reference_tolerance", general(defaults.referenceTolerance));
  recordValue(options, "cost.repeats", std::to_string(plan.repeats));
  recordValue(options, "cost.failure", describe(options.criterion));
}

void writeSafeRows(Csv& csv, const CostScene& scene, const Surveyed& survey) {
  for (const auto& scan : survey.integrators) {
    csv << scene.label << scene.horizon << scan.integrator << (scan.adaptive ? std::nan("") : scan.safeDt)
        << scan.firstFailureDt << scan.runs << scan.ensembleRuns;
    csv.endRow();
  }
}

// A row per found pick; `cheapest` marks the one the table names (ties are marked apart).
void writePickRows(Csv& csv, const CostScene& scene, const Surveyed& survey, double relative,
                   std::vector<Pick> picks) {
  const double budget = relative * survey.size;
  const int best = cheapest(picks);
  markTies(picks, best);
  for (std::size_t k = 0; k < picks.size(); ++k) {
    if (!picks[k].found) continue;
    const Pick& p = picks[k];
    const Candidate& candidate = p.candidate;
    csv << scene.label << static_cast<long>(survey.particles) << scene.horizon << survey.size << relative << budget
        << candidate.integrator << candidate.dt << candidate.tolerance << candidate.maxError << p.worstError
        << survey.integrators[k].safeDt << p.cpuPerSimulatedSecond << p.cpuMin << p.cpuMax
        << survey.referenceAgreement << p.certifiedLo << p.certifiedHi << p.marginRuns.runs
        << p.marginRuns.failures << p.marginRuns.upperBound() << static_cast<long>(static_cast<int>(k) == best)
        << static_cast<long>(p.tie);
    csv.endRow();
  }
}

// The table's columns after scene and budget: the cheapest pick, or why there is none.
std::vector<std::string> cheapestText(const CostScene& scene, const Surveyed& survey, double budget,
                                      std::vector<Pick> picks) {
  if (!measurable(budget, survey.referenceAgreement))
    return {"reference not converged (tolerances differ by " + general(survey.referenceAgreement, 2) + ")", "–", "–",
            "–", "–"};
  const int best = cheapest(picks);
  if (best < 0) return {"none within budget (grid down to dt = " + general(scene.horizon / scene.maxSteps) + ")", "–",
                        "–", "–", "–"};
  markTies(picks, best);
  const auto& pick = picks[best];
  std::string name = pick.candidate.integrator, ties;
  for (const Pick& p : picks)
    if (p.tie) ties += (ties.empty() ? "" : ", ") + p.candidate.integrator;
  if (!ties.empty()) name += " (tie: " + ties + ")";
  const std::string step =
      general(pick.candidate.dt) + (pick.candidate.tolerance > 0 ? ", tol " + general(pick.candidate.tolerance) : "");
  const std::string margin = pick.certified() ? (pick.candidate.tolerance > 0 ? "tol " : "dt ") +
                                                    general(pick.certifiedLo, 3) + "–" + general(pick.certifiedHi, 3) +
                                                    " (" + boundText(pick.marginRuns) + ")"
                                              : "–";
  return {name, step, general(pick.error()),
          general(pick.cpuPerSimulatedSecond) + " (" + general(pick.cpuMin, 2) + "–" + general(pick.cpuMax, 2) + ")",
          margin};
}

// Where each integrator is the cheapest pick: "the 16x16 cloth at a budget of 0.01", ...
using CheapestWhere = std::map<std::string, std::vector<std::string>>;

// The cheapest found pick's integrator at a measurable budget, or "".
std::string cheapestName(const Surveyed& survey, double budget, const std::vector<Pick>& picks) {
  if (!measurable(budget, survey.referenceAgreement)) return "";
  const int best = cheapest(picks);
  return best < 0 ? "" : picks[best].candidate.integrator;
}

// For the report's advice (§5), per integrator of the table: "is the cheapest pick for A, B and
// C" or "is never the cheapest pick": what the cost tables say, as a clause.
void recordCheapestWhere(const LabOptions& options, const CheapestWhere& where) {
  for (const auto& info : particles::integratorTable()) {
    const auto found = where.find(info.name);
    std::string clause = "is never the cheapest pick in the cost tables";
    if (found != where.end() && !found->second.empty()) {
      clause = "is the cheapest pick for ";
      const auto& places = found->second;
      for (std::size_t k = 0; k < places.size(); ++k)
        clause += (k == 0 ? "" : k + 1 == places.size() ? " and " : ", ") + places[k];
    }
    recordValue(options, std::string("cost.where_cheapest.") + info.name, clause);
  }
}

void writeResults(const LabOptions& options, const CostPlan& plan, const Results<Surveyed>& surveys,
                  CheapestWhere& where) {
  Csv picksCsv(options, "cost_of_accuracy.csv",
               {"scene", "particles", "horizon", "size", "budget_relative", "budget", "integrator", "dt", "tolerance",
                "max_error", "worst_error", "surviving_dt", "cpu_per_simulated_second", "cpu_min", "cpu_max",
                "reference_agreement", "certified_lo", "certified_hi", "margin_runs", "margin_failures",
                "failure_bound", "cheapest", "tie"});
  Csv safeCsv(options, "cost_safe_dt.csv",
              {"scene", "horizon", "integrator", "surviving_dt", "first_failure_dt", "runs", "ensemble_runs"});
  std::vector<std::vector<std::string>> table;
  for (const auto& [k, survey] : surveys) {
    const CostScene& scene = plan.scenes[k];
    writeSafeRows(safeCsv, scene, survey);
    const std::string label = scene.label + " (" + output::plural(survey.particles, "particle") + ", T = " +
                              general(scene.horizon) + " s)";
    for (std::size_t b = 0; b < kBudgets.size(); ++b) {
      const double relative = kBudgets[b], budget = relative * survey.size;
      std::vector<std::string> row{label, general(relative) + " (" + general(budget, 2) + ")"};
      if (measurable(budget, survey.referenceAgreement))
        writePickRows(picksCsv, scene, survey, relative, survey.picks[b]);
      const std::vector<std::string> cheapestColumns = cheapestText(scene, survey, budget, survey.picks[b]);
      row.insert(row.end(), cheapestColumns.begin(), cheapestColumns.end());
      table.push_back(row);
      const std::string name = cheapestName(survey, budget, survey.picks[b]);
      if (!name.empty()) where[name].push_back("the " + scene.label + " at a budget of " + general(relative));
    }
  }
  writeTable(options, "cost_of_accuracy",
             "The cost of accuracy: cheapest integrator and dt whose max particle position error over [0, T] "
             "against the reference is within the budget (relative to the scene's size; absolute in brackets), "
             "at dt <= 0.8 x the coarse scan's largest surviving dt, certified: every dt (adaptive: tolerance) " +
                 general(100.0 * SurveySettings{}.certifyResolution) + "% apart in its margin survives within the "
                 "budget on " + output::plural(SurveySettings{}.certifyMembers, "start") +
                 " (max error: the largest over them at the pick), with the 95% bound p on the per-run probability "
                 "of a failure or a miss that the margin's runs support; CPU seconds per simulated second, median of "
                 "repeats interleaved across the picks (min–max); a tie: a pick whose range overlaps the cheapest's",
             {"scene", "budget", "cheapest", "dt", "max error", "CPU s / simulated s", "certified margin (bound)"},
             table);
}

// Every surveyed scene in cell order: the scenes, then each family's sizes in turn.
struct Surveyable {
  const CostScene* scene;
  const std::vector<double>* budgets;
  int family;  // index into CostPlan::families, −1 for the scenes
};
std::vector<Surveyable> surveyables(const CostPlan& plan) {
  std::vector<Surveyable> all;
  for (const CostScene& scene : plan.scenes) all.push_back({&scene, &kBudgets, -1});
  for (std::size_t f = 0; f < plan.families.size(); ++f)
    for (const CostScene& scene : plan.families[f].sizes) all.push_back({&scene, &kSizeBudgets, static_cast<int>(f)});
  return all;
}

// The size families: every size's cheapest pick per budget (cost_vs_size.csv
// and its table), and per family and budget the fitted slope of log CPU time
// per simulated second against log particle count over the sizes with a pick.
void writeSizeResults(const LabOptions& options, const CostPlan& plan, const std::vector<Surveyable>& all,
                      const Results<Surveyed>& surveys, CheapestWhere& where) {
  Csv csv(options, "cost_vs_size.csv",
          {"family", "scene", "particles", "horizon", "size", "budget_relative", "integrator", "dt", "tolerance",
           "max_error", "worst_error", "cpu_per_simulated_second", "cpu_min", "cpu_max", "reference_agreement",
           "certified_lo", "certified_hi", "margin_runs", "failure_bound"});
  std::vector<std::vector<std::string>> table, slopes;
  for (std::size_t f = 0; f < plan.families.size(); ++f) {
    const SizeFamily& family = plan.families[f];
    for (std::size_t b = 0; b < kSizeBudgets.size(); ++b) {
      std::vector<double> particles, cpu;
      for (const auto& [k, survey] : surveys) {
        if (all[k].family != static_cast<int>(f)) continue;
        const CostScene& scene = *all[k].scene;
        const double relative = kSizeBudgets[b], budget = relative * survey.size;
        std::vector<std::string> row{family.name, std::to_string(survey.particles), general(scene.horizon),
                                     general(relative)};
        const std::vector<std::string> columns = cheapestText(scene, survey, budget, survey.picks[b]);
        row.insert(row.end(), columns.begin(), columns.end());
        table.push_back(row);
        const int best = measurable(budget, survey.referenceAgreement) ? cheapest(survey.picks[b]) : -1;
        if (best < 0) continue;
        const Pick& pick = survey.picks[b][best];
        where[pick.candidate.integrator].push_back("the " + std::to_string(survey.particles) + "-particle " +
                                                   family.name + " at " + general(relative));
        csv << family.name << scene.label << static_cast<long>(survey.particles) << scene.horizon << survey.size
            << relative << pick.candidate.integrator << pick.candidate.dt << pick.candidate.tolerance
            << pick.candidate.maxError << pick.worstError << pick.cpuPerSimulatedSecond << pick.cpuMin
            << pick.cpuMax << survey.referenceAgreement << pick.certifiedLo << pick.certifiedHi
            << pick.marginRuns.runs << pick.marginRuns.upperBound();
        csv.endRow();
        particles.push_back(survey.particles);
        cpu.push_back(pick.cpuPerSimulatedSecond);
      }
      const double slope = logLogSlope(particles, cpu);
      const std::string text = std::isfinite(slope) ? fixed(slope, 2) : "–";
      slopes.push_back({family.name, general(kSizeBudgets[b]), text, std::to_string(particles.size())});
      recordValue(options, "cost.size_slope." + family.name + "." + general(kSizeBudgets[b]), text);
    }
  }
  recordValue(options, "cost.size_horizon", general(plan.families.empty() ? 0.0 : plan.families[0].sizes[0].horizon));
  writeTable(options, "cost_vs_size",
             "The cost of accuracy against size: per family, size and budget (relative to the scene's size), the "
             "cheapest integrator and dt within the budget over [0, T], chosen and certified as in the cost table "
             "(its margin and bound); CPU seconds per simulated second, median of interleaved repeats (min–max)",
             {"family", "particles", "T (s)", "budget", "cheapest", "dt", "max error", "CPU s / simulated s",
              "certified margin (bound)"},
             table);
  writeTable(options, "cost_size_slopes",
             "Growth of the cheapest choice's cost with size: fitted slope of log CPU s per simulated s against log "
             "particle count, over the sizes with a pick",
             {"family", "budget", "slope", "sizes fitted"}, slopes);
}

// One contact question's answer: the reference (or why there is none) and the picks.
struct ContactAnswer {
  int particles = 0;
  std::string contact, reference, limit;
  double certifiableHorizon = 0.0;
  std::vector<Pick> picks;
  int best = -1;
};
template <class Io>
void fields(Io& io, ContactAnswer& a) {
  io("particles", a.particles), io("contact", a.contact), io("reference", a.reference), io("limit", a.limit);
  io("certifiable_horizon", a.certifiableHorizon), io("picks", a.picks), io("best", a.best);
}

std::optional<ContactAnswer> adviseOnContacts(const LabOptions& options, const CostPlan& plan,
                                              const ContactQuestion& q) {
  SurveySettings settings;
  settings.horizon = q.horizon;
  settings.targetError = settings.abortError = q.error;
  settings.integrators = selectedIntegrators(options);
  settings.repeats = plan.repeats;
  settings.certifyMembers = plan.contactStarts;
  settings.failure = options.criterion;
  const Advice advice = advise([&] { return scenes::buildScene(q.scene, q.params); }, settings);
  if (!advice.complete) return std::nullopt;
  return ContactAnswer{advice.survey.particles, advice.survey.contact, advice.survey.reference,
                       advice.survey.limit, advice.survey.certifiableHorizon, advice.picks, advice.best};
}

// The command that asks the same question.
std::string adviseCommand(const ContactQuestion& q, int starts) {
  std::string command = "particle-lab advise --scene " + q.scene;
  for (const auto& [key, value] : q.params) command += " --param " + key + "=" + value;
  return command + " --error " + general(q.error) + " --horizon " + general(q.horizon) + " --certify-starts " +
         std::to_string(starts);
}

// The contact table: per question its reference or refusal, and the cheapest certified pick.
void writeContactResults(const LabOptions& options, const CostPlan& plan, const Results<ContactAnswer>& answers) {
  Csv csv(options, "cost_contacts.csv",
          {"scene", "particles", "horizon", "error", "contact", "reference", "refused", "certifiable_horizon",
           "integrator", "dt", "worst_error", "headroom", "certified_lo", "certified_hi", "margin_runs",
           "failure_bound", "cpu_per_simulated_second"});
  std::vector<std::vector<std::string>> table;
  for (const auto& [k, a] : answers) {
    const ContactQuestion& q = plan.contacts[k];
    const bool refused = !a.limit.empty();
    const Pick* pick = a.best >= 0 ? &a.picks[a.best] : nullptr;
    csv << q.label << static_cast<long>(a.particles) << q.horizon << q.error << a.contact << a.reference
        << static_cast<long>(refused) << a.certifiableHorizon << (pick ? pick->candidate.integrator : "")
        << (pick ? pick->candidate.dt : 0.0) << (pick ? pick->error() : 0.0)
        << (pick ? headroom(*pick, q.error) : 0.0) << (pick ? pick->certifiedLo : 0.0)
        << (pick ? pick->certifiedHi : 0.0) << (pick ? pick->marginRuns.runs : 0L)
        << (pick ? pick->marginRuns.upperBound() : 1.0) << (pick ? pick->cpuPerSimulatedSecond : 0.0);
    csv.endRow();
    std::string answer;
    if (refused)
      answer = "refuses: " + a.limit + "; certifiable over " + general(a.certifiableHorizon, 3) + " s";
    else if (!pick)
      answer = "finds no integrator that meets E within its safe range";
    else
      answer = "answers " + pickArguments(pick->candidate) + ", max error " + general(pick->error(), 2) + " over " +
               output::plural(pick->starts, "start") + " (headroom " + fixed(100.0 * headroom(*pick, q.error), 0) +
               "%), margin dt " + general(pick->certifiedLo, 3) + "–" + general(pick->certifiedHi, 3) + ", " +
               boundText(pick->marginRuns);
    table.push_back({q.label + " (" + output::plural(a.particles, "particle") + ")", general(q.horizon),
                     general(q.error), a.contact.empty() ? "–" : a.contact, refused ? "–" : a.reference, answer});
    recordValue(options, "cost.contacts." + std::to_string(k) + ".command", adviseCommand(q, plan.contactStarts));
    recordValue(options, "cost.contacts." + std::to_string(k) + ".answer", answer);
  }
  recordValue(options, "cost.contact_starts", std::to_string(plan.contactStarts));
  writeTable(options, "cost_contacts",
             "Advice on scenes with contacts (demo defaults, `particle-lab advise`): the contact the odeint "
             "reference meets, the reference by self-convergence of the contact-aware schemes (dt halved until "
             "two runs agree within E/10) or why there is none, and the cheapest pick certified on " +
                 output::plural(plan.contactStarts, "start") +
                 " per margin dt (its error within E at every dt of the margin, on every start), with the 95% "
                 "bound on the per-run failure probability its margin's runs support",
             {"scene", "T (s)", "E", "contact", "reference", "answer"}, table);
}

}  // namespace

int runCost(const LabOptions& options) {
  prepareOutput(options, "cost.");
  const CostPlan plan = options.quick ? quickPlan() : fullPlan();
  recordSettings(options, plan);
  const std::vector<Surveyable> all = surveyables(plan);
  Progress progress(options, "cost", static_cast<long>(all.size()));
  // One scene at a time: the picks' CPU times are measurements.
  const auto surveys = resultsInTurn<Surveyed>(
      options, all.size(),
      [&](std::size_t k) {
        const Surveyable& s = all[k];
        return surveyCostScene(*s.scene, surveySettings(options, plan, *s.scene, *s.budgets), *s.budgets);
      },
      true, [&](std::size_t) { progress.tick(); });
  Results<Surveyed> scenes, sizes;
  for (const auto& [k, survey] : surveys) (all[k].family < 0 ? scenes : sizes).emplace(k, survey);
  CheapestWhere where;
  writeResults(options, plan, scenes, where);
  writeSizeResults(options, plan, all, sizes, where);
  recordCheapestWhere(options, where);
  if (interrupted()) return 130;
  Progress contactProgress(options, "cost: contacts", static_cast<long>(plan.contacts.size()));
  const auto answers = resultsInTurn<ContactAnswer>(
      options, plan.contacts.size(), [&](std::size_t k) { return adviseOnContacts(options, plan, plan.contacts[k]); },
      true, [&](std::size_t) { contactProgress.tick(); });
  writeContactResults(options, plan, answers);
  return interrupted() ? 130 : 0;
}

}  // namespace lab
