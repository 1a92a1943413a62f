// The accuracy side of the laboratory: the odeint reference against the
// oscillator's closed form, and `advise` against a brute-force search of the
// same grid with errors taken from the closed form.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "lab/advise.h"
#include "lab/lab_scene.h"
#include "lab/reference.h"
#include "lab/scan.h"
#include "scenes/oscillator.h"
#include "scenes/pendulum.h"
#include "scene_file/scene_file.h"

using namespace lab;

// A survey's horizon T and error budget E (the abort error too), and the
// integrators it tries (all of them when none are named).
static SurveySettings surveyAt(double horizon, double error, std::vector<std::string> integrators = {}) {
  SurveySettings settings;
  settings.horizon = horizon;
  settings.targetError = settings.abortError = error;
  if (!integrators.empty()) settings.integrators = std::move(integrators);
  return settings;
}


namespace {

// Max over the run's steps of the bob's distance from the closed form.
double closedFormError(const Candidate& c, double horizon, long* evaluations = nullptr) {
  const scenes::OscillatorParams p;
  scenes::Scene scene = scenes::buildScene("oscillator");
  long count = 0;  // force evaluations, as each step reports them (StepStats)
  particles::IntegratorSettings settings;
  if (c.tolerance > 0) settings.dopri5.tolerance = c.tolerance;
  auto stepper = particles::makeIntegrator(c.integrator, settings);
  double worst = 0.0;
  const long steps = std::lround(horizon / c.dt);
  for (long k = 1; k <= steps; ++k) {
    count += scene.system->step(*stepper, c.dt).forceEvaluations;
    const Eigen::Vector2d exact(p.rest + scenes::oscillatorDisplacement(p, k * c.dt), 0.0);
    worst = std::max(worst, (scene.system->position(1) - exact).norm());
  }
  if (evaluations) *evaluations = count;
  return worst;
}

}  // namespace

TEST(OdeintReference, MatchesTheOscillatorClosedForm) {
  const double horizon = 32.0;  // five periods of ω = 1
  scenes::Scene scene = scenes::buildScene("oscillator");
  ReferenceSettings settings;
  settings.interval = 0.05;
  const Trajectory odeint = odeintReference(scene, horizon, settings);
  const Trajectory exact = oscillatorReference({}, horizon, settings.interval);
  ASSERT_EQ(odeint.x.size(), exact.x.size());
  EXPECT_NEAR(odeint.duration(), horizon, 1e-12);
  // The bob moves 0.3 at first: a reference that stood still would be 0.3 off.
  EXPECT_LT(maxTrajectoryDistance(odeint, exact), 1e-8);
  // Between samples the Hermite interpolant keeps that accuracy.
  const scenes::OscillatorParams p;
  for (double t : {0.013, 7.77, 31.99}) {
    const double x = odeint.positionsAt(t)(2);
    EXPECT_NEAR(x, p.rest + scenes::oscillatorDisplacement(p, t), 1e-8) << "t = " << t;
  }
  // A loose tolerance with sparse samples (odeint's steps then grow) is
  // measurably worse: the comparison can tell references apart.
  scenes::Scene again = scenes::buildScene("oscillator");
  settings.tolerance = 1e-3;
  settings.interval = 4.0;
  EXPECT_GT(maxTrajectoryDistance(odeintReference(again, horizon, settings),
                                  oscillatorReference({}, horizon, settings.interval)),
            1e-8);
}

// The slowest period measured on a reference (what the accuracy horizons are
// counted in) is the large-angle pendulum's elliptic-integral period; a
// pendulum hanging at rest has none.
TEST(OdeintReference, SlowestPeriodIsThePendulumsPeriod) {
  scenes::PendulumParams p;
  const double period = scenes::pendulumPeriod(p);
  scenes::Scene swinging = scenes::buildPendulum(p);
  ReferenceSettings settings;
  settings.tolerance = 1e-9;
  const Trajectory swing = odeintReference(swinging, 5.5 * period, settings);
  EXPECT_NEAR(swing.slowestPeriod(), period, 1e-3 * period);
  // The height swings at twice the frequency: over 0.9 periods it alone
  // crosses twice, over 0.4 nothing does.
  scenes::Scene shorter = scenes::buildPendulum(p);
  EXPECT_NEAR(odeintReference(shorter, 0.9 * period, settings).slowestPeriod(), 0.5 * period, 2e-3 * period);
  scenes::Scene brief = scenes::buildPendulum(p);
  EXPECT_EQ(odeintReference(brief, 0.4 * period, settings).slowestPeriod(), 0.0);
  p.angle = 0.0;
  scenes::Scene hanging = scenes::buildPendulum(p);
  EXPECT_EQ(odeintReference(hanging, 3.0 * period, settings).slowestPeriod(), 0.0);
}

TEST(Advise, OscillatorPickMeetsTheClosedFormAndIsNearlyTheCheapestGridPoint) {
  const double error = 1e-4, horizon = 32.0;
  SurveySettings settings = surveyAt(horizon, error);
  settings.maxSteps = 20000;
  settings.repeats = 3;
  const auto build = [] { return scenes::buildScene("oscillator"); };
  const Survey survey = surveyScene(build, settings);
  const auto picks = pickPerIntegrator(build, survey, settings, error);
  const int best = cheapest(picks);
  ASSERT_GE(best, 0);
  const Candidate& chosen = picks[best].candidate;
  long chosenCost = 0;
  EXPECT_LE(closedFormError(chosen, horizon, &chosenCost), error) << pickArguments(chosen);

  // Brute force over every integrator's scanned grid: the cheapest point whose
  // closed-form error is within E and that survives, by force evaluations.
  long cheapestCost = -1;
  std::string cheapestName;
  for (const auto& scan : survey.integrators)
    for (const auto& c : scan.scanned) {
      long cost = 0;
      if (!c.survived || closedFormError(c, horizon, &cost) > error) continue;
      if (cheapestCost < 0 || cost < cheapestCost) cheapestCost = cost, cheapestName = pickArguments(c);
    }
  ASSERT_GT(cheapestCost, 0);
  EXPECT_LE(chosenCost, 2 * cheapestCost) << "chose " << pickArguments(chosen) << ", cheapest " << cheapestName;
}

// An energy budget is a budget: on the pendulum at E = 1e-2, the position
// budget alone lets the picks' energy errors exceed 1e-4 of E_s; with that
// energy budget (and a constraint-drift budget) every pick meets both, and
// the pick is rerun from its options with the same energy error.
TEST(Advise, EnergyAndDriftBudgetsAreMetByEveryPick) {
  const auto build = [] { return scenes::buildScene("pendulum"); };
  SurveySettings settings = surveyAt(20.0, 1e-2, {"rk4", "verlet", "midpoint"});
  settings.repeats = 1;
  settings.certifyMembers = 0;
  const double energy = 1e-4, drift = 1e-5;
  const Advice loose = advise(build, settings);
  ASSERT_TRUE(loose.complete);
  double worstLoose = 0.0;
  for (const Pick& p : loose.picks)
    if (p.found) worstLoose = std::max(worstLoose, p.candidate.energyError);
  ASSERT_GT(worstLoose, energy) << "the position budget alone already meets the energy budget: no test";

  settings.energyBudget = energy;
  settings.driftBudget = drift;
  const Advice tight = advise(build, settings);
  ASSERT_TRUE(tight.complete);
  ASSERT_GE(tight.best, 0);
  for (const Pick& p : tight.picks) {
    if (!p.found) continue;
    EXPECT_LE(p.candidate.energyError, energy) << pickArguments(p.candidate);
    EXPECT_LE(p.candidate.constraintDrift, drift) << pickArguments(p.candidate);
    EXPECT_LE(p.candidate.maxError, 1e-2) << pickArguments(p.candidate);
  }
  const Candidate& best = tight.picks[tight.best].candidate;
  const Candidate again = measureRun(build, *tight.survey.referenceTrajectory, best.integrator, best.dt,
                                     best.tolerance, settings.horizon, settings.failure, tight.survey.energyScale);
  EXPECT_NEAR(again.energyError, best.energyError, 1e-12 + 1e-9 * best.energyError);
}

TEST(Advise, APrintedPickRerunFromItsOptionsReproducesItsError) {
  // The options printed for a pick (pickArguments) are read back as a user
  // would and rerun: the closed-form error of the rerun is within 10% of the
  // error the survey measured for the pick against its reference.
  const double error = 1e-4, horizon = 16.0;
  SurveySettings settings = surveyAt(horizon, error, {"dopri5", "rk4", "verlet"});
  settings.maxSteps = 20000;
  settings.repeats = 1;
  const auto build = [] { return scenes::buildScene("oscillator"); };
  const Survey survey = surveyScene(build, settings);
  ASSERT_TRUE(survey.limit.empty()) << survey.limit;
  const auto picks = pickPerIntegrator(build, survey, settings, error);
  int found = 0;
  for (const Pick& pick : picks) {
    if (!pick.found) continue;
    ++found;
    std::istringstream words(pickArguments(pick.candidate));
    Candidate rerun;
    for (std::string word; words >> word;) {
      if (word == "--integrator") words >> rerun.integrator;
      if (word == "--dt") words >> rerun.dt;
      if (word == "--tolerance") words >> rerun.tolerance;
    }
    EXPECT_EQ(rerun.integrator, pick.candidate.integrator);
    EXPECT_EQ(rerun.dt, pick.candidate.dt);
    EXPECT_EQ(rerun.tolerance, pick.candidate.tolerance);
    EXPECT_NEAR(closedFormError(rerun, horizon), pick.candidate.maxError, 0.1 * pick.candidate.maxError)
        << pickArguments(pick.candidate);
  }
  EXPECT_EQ(found, 3);
}

TEST(Advise, PastTheChaoticHorizonSaysSoAndNamesTheHorizonItCanCertify) {
  // The rod chain's two references part by more than E/10 = 1e-3 within 10 s:
  // no integrator is scanned, and the horizon named as certifiable is
  // certified when asked for (the references agree within E/10 over it).
  SurveySettings settings = surveyAt(10.0, 1e-2, {"rk4"});
  settings.repeats = 1;
  const auto build = [] { return scenes::buildScene("rod-chain"); };
  const Survey survey = surveyScene(build, settings);
  EXPECT_NE(survey.limit.find("not predictable"), std::string::npos) << survey.limit;
  EXPECT_TRUE(survey.integrators.empty());
  EXPECT_GT(survey.certifiableHorizon, 1.0);
  EXPECT_LT(survey.certifiableHorizon, 10.0);
  settings.horizon = survey.certifiableHorizon;
  const Survey shorter = surveyScene(build, settings);
  EXPECT_TRUE(shorter.limit.empty()) << shorter.limit;
  EXPECT_LE(shorter.referenceAgreement, 1e-3);
  ASSERT_EQ(shorter.integrators.size(), 1u);
}

TEST(Advise, AReferenceThatMeetsAContactNamesItAndWithoutContactReferencesCertifiesNothingPastIt) {
  // The hair's discs meet one another early (it has no walls); odeint models
  // no contact, so with contact references off advise names the contact (the
  // discs that touch, and when) and a shorter horizon.
  SurveySettings settings = surveyAt(0.2, 1e-3, {"rk4"});
  settings.repeats = 1;
  settings.contactReference = false;
  const Survey survey = surveyScene([] { return scenes::buildScene("hair"); }, settings);
  EXPECT_TRUE(survey.touchedWall);
  EXPECT_NE(survey.contact.find("the discs of particles"), std::string::npos) << survey.contact;
  EXPECT_NE(survey.contact.find("touch at t = "), std::string::npos) << survey.contact;
  EXPECT_NE(survey.limit.find(survey.contact), std::string::npos) << survey.limit;
  EXPECT_EQ(survey.limit.find("wall"), std::string::npos) << survey.limit;
  EXPECT_TRUE(survey.integrators.empty());
  EXPECT_LT(survey.certifiableHorizon, 0.2);
}

namespace {

// A finer run than the reference: its scheme at half its step, sampled as it is.
Trajectory finerRun(const std::function<scenes::Scene()>& build, const Survey& survey) {
  const SelfConvergence& r = survey.contactReference;
  const long stride = std::lround(survey.referenceTrajectory->interval / r.dt);
  const std::optional<Trajectory> finer =
      steppedTrajectory(build, r.scheme, 0.5 * r.dt, 2 * stride, survey.horizon, FailureCriterion{});
  EXPECT_TRUE(finer.has_value());
  return finer ? *finer : Trajectory{};
}

// What advise must do on a scene with contacts: its contact reference
// converges (two successive halvings within E/10, an order observed) and its
// pick is within E of a run finer than the reference, from every start it
// claims. (A budget self-convergence cannot reach is refused: the CLI test
// advise.contacts-not-converged.)
void expectContactAdvice(const std::function<scenes::Scene()>& build, SurveySettings settings, const char* what) {
  const double error = settings.targetError;
  const Advice advice = advise(build, settings);
  ASSERT_TRUE(advice.complete) << what;
  const Survey& survey = advice.survey;
  ASSERT_TRUE(survey.touchedWall) << what << ": the scene meets no contact: no test";
  const SelfConvergence& reference = survey.contactReference;
  ASSERT_GE(reference.halvings.size(), 1u) << what;
  ASSERT_TRUE(reference.converged) << what << ": " << survey.limit;
  EXPECT_TRUE(survey.limit.empty()) << what << ": " << survey.limit;
  EXPECT_LE(reference.difference, error / 10.0) << what;
  EXPECT_NE(survey.reference.find("self-convergence of " + reference.scheme), std::string::npos) << survey.reference;
  EXPECT_NEAR(reference.dt, reference.halvings.back().dt, 1e-15) << what;
  ASSERT_GE(advice.best, 0) << what << ": the reference converged but nothing meets E";
  const Pick& pick = advice.picks[advice.best];
  ASSERT_TRUE(pick.certified()) << what;
  EXPECT_LE(pick.error(), error) << what;
  EXPECT_GE(pick.worstError, pick.candidate.maxError) << what;
  // The pick against a run twice as fine as the reference, from every start it was certified on.
  const Trajectory fine = finerRun(build, survey);
  for (int member = 0; member < pick.starts; ++member) {
    const auto perturbed = [&] {
      scenes::Scene scene = build();
      perturbStart(scene, member);
      return scene;
    };
    const Candidate again = measureRun(perturbed, fine, pick.candidate.integrator, pick.candidate.dt,
                                       pick.candidate.tolerance, settings.horizon, settings.failure, 1.0);
    EXPECT_TRUE(again.survived) << what << " start " << member;
    EXPECT_LE(again.maxError, error) << what << " " << pickArguments(pick.candidate) << " start " << member;
  }
}

SurveySettings contactSettings(double horizon, double error) {
  SurveySettings settings = surveyAt(horizon, error, {"symplectic-euler", "rk4", "verlet"});
  settings.repeats = 1;
  settings.certifyMembers = 3;
  settings.maxSteps = 20000;
  return settings;
}

}  // namespace

// A small hair (2 strands of 12) whose discs meet within 0.2 s.
TEST(Advise, AHairWithContactsGetsAPickAFinerRunConfirms) {
  expectContactAdvice([] { return scenes::buildScene("hair", {{"curls", "2"}, {"particles", "12"}}); },
                      contactSettings(0.2, 1e-3), "hair");
}

// Discs falling through a funnel of two capsules onto a floor (the example
// scene file capsule.json): impacts with restitution and friction.
TEST(Advise, DiscsInAFunnelGetAPickAFinerRunConfirms) {
  const std::string file = std::string(SCENES_DIR) + "/capsule.json";
  expectContactAdvice([&] { return scenes::loadSceneFile(file); }, contactSettings(3.0, 1e-3), "funnel");
}

TEST(Advise, NothingWithinAnUnreachableBudget) {
  SurveySettings settings = surveyAt(10.0, 1e-6, {"euler"});
  settings.maxSteps = 2000;
  settings.repeats = 1;
  const auto build = [] { return scenes::buildScene("oscillator"); };
  const Survey survey = surveyScene(build, settings);
  const auto picks = pickPerIntegrator(build, survey, settings, 1e-6);
  ASSERT_EQ(picks.size(), 1u);
  EXPECT_FALSE(picks[0].found);
  EXPECT_EQ(cheapest(picks), -1);
}

TEST(Advise, RejectsBadSettingsNamingTheField) {
  SurveySettings settings;
  settings.horizon = -1.0;
  const auto build = [] { return scenes::buildScene("oscillator"); };
  EXPECT_THROW(surveyScene(build, settings), std::invalid_argument);
  settings.horizon = 1.0;
  settings.integrators = {"rk5"};
  EXPECT_THROW(surveyScene(build, settings), std::invalid_argument);
}

TEST(Advise, ACancelledSurveyIsIncompleteAndNamesNoPick) {
  SurveySettings settings = surveyAt(5.0, 1e-2);
  settings.repeats = 1;
  settings.certifyMembers = 2;
  const auto build = [] { return scenes::buildScene("pendulum"); };
  // Cancelled while the reference is computed (the flag is already set) ...
  std::atomic<bool> cancel{true};
  settings.cancel = &cancel;
  const Advice before = advise(build, settings);
  EXPECT_FALSE(before.complete);
  EXPECT_EQ(before.best, -1);
  // ... and during the scan: the first progress past the reference sets it.
  cancel = false;
  double reached = 0.0;
  settings.progress = [&](double f) {
    reached = std::max(reached, f);
    if (f > 0.0) cancel = true;
  };
  const Advice during = advise(build, settings);
  EXPECT_FALSE(during.complete);
  EXPECT_EQ(during.best, -1);
  EXPECT_LT(reached, 0.9) << "the scan stopped before the timing";
  // Uncancelled, the same request is complete and names the cheapest.
  cancel = false;
  settings.progress = {};
  const Advice whole = advise(build, settings);
  EXPECT_TRUE(whole.complete);
  ASSERT_GE(whole.best, 0);
  EXPECT_LE(whole.picks[whole.best].candidate.maxError, 1e-2);
}

TEST(Advise, SafeBoundaryIsTheLabsScanOverTheEnsemble) {
  // The 6-chain over 5 s: fixed-step schemes fail at the top of the grid.
  const auto build = [] { return buildLabScene("test-chain", {{"cl", "6"}}); };
  SurveySettings settings = surveyAt(5.0, 1e-3);
  settings.maxSteps = 1000;
  settings.repeats = 1;
  settings.integrators = {"symplectic-euler", "midpoint", "rk4"};
  const Survey survey = surveyScene(build, settings);
  int bounded = 0;
  for (const IntegratorSurvey& scan : survey.integrators) {
    ASSERT_FALSE(scan.scanned.empty()) << scan.integrator;
    if (scan.firstFailureDt == 0.0) continue;
    ++bounded;
    EXPECT_GT(scan.ensembleRuns, 0) << scan.integrator;
    // The lab's scan (scan.h) of the same grid points, every member from the
    // bottom up, gives the same boundary.
    ScanSettings lab;
    lab.members = settings.members;
    lab.beyond = 1e9;
    for (const Candidate& c : scan.scanned) lab.grid.insert(lab.grid.begin(), c.dt);
    const std::optional<Boundary> b = scanSafeStep(build, scan.integrator, settings.horizon, lab, settings.failure);
    ASSERT_TRUE(b.has_value());
    EXPECT_EQ(scan.safeDt, b->safeDt) << scan.integrator;
    EXPECT_EQ(scan.firstFailureDt, b->firstFailureDt) << scan.integrator;
  }
  EXPECT_GT(bounded, 0) << "some scheme fails on the grid";
}

// The seed 24-chain under RK4 over 50 s at E 0.5: the largest scanned dt
// within the budget fails on some start inside its margin (survival is
// chaotic in dt there), so the certified pick is lower; halfway between the
// 1% grid points of its certified margin, on the same starts, no run fails
// either.
TEST(Advise, APickIsMovedBelowTheFailuresInItsMarginAndHoldsBetweenItsGridPoints) {
  const double horizon = 50.0, error = 0.5;
  const auto build = [] { return buildLabScene("test-chain", {{"cl", "24"}}); };
  SurveySettings settings = surveyAt(horizon, error);
  settings.repeats = 1;
  settings.integrators = {"rk4"};
  const Survey survey = surveyScene(build, settings);
  ASSERT_TRUE(survey.limit.empty()) << survey.limit;
  SurveySettings uncertified = settings;
  uncertified.certifyMembers = 0;
  const Pick scanned = pickPerIntegrator(build, survey, uncertified, error).at(0);
  const Pick certified = pickPerIntegrator(build, survey, settings, error).at(0);
  ASSERT_TRUE(scanned.found);
  ASSERT_TRUE(certified.found) << certified.uncertified;
  EXPECT_EQ(scanned.certifiedHi, 0.0);
  EXPECT_LT(certified.candidate.dt, scanned.candidate.dt);
  EXPECT_LE(certified.candidate.maxError, error);
  EXPECT_NEAR(certified.certifiedHi, certified.candidate.dt / settings.safeFraction, 0.011 * certified.certifiedHi);
  EXPECT_NEAR(certified.certifiedLo, certified.candidate.dt * settings.safeFraction, 0.011 * certified.certifiedLo);
  const double between = std::sqrt(std::pow(2.0, 1.0 / stepsPerOctave(settings.certifyResolution)));
  for (double dt = certified.certifiedLo * between; dt < certified.certifiedHi; dt *= between * between)
    for (int member = 0; member < settings.certifyMembers; ++member)
      ASSERT_TRUE(runMember(build, "rk4", dt, member, horizon, settings.failure)->survives(horizon, dt))
          << "dt " << dt << " start " << member;
}

// The margin of a fixed-step pick keeps the error within E, not only the
// run alive: on the pendulum every dt of each certified margin (and between
// its 1% grid points) is within E of the reference from the start as built,
// and a pick whose margin's top missed E was moved below it.
TEST(Advise, AFixedStepPicksMarginKeepsTheErrorWithinE) {
  const double error = 1e-3, horizon = 20.0;
  const auto build = [] { return scenes::buildScene("pendulum"); };
  SurveySettings settings = surveyAt(horizon, error, {"midpoint", "rk4", "verlet"});
  settings.repeats = 1;
  settings.certifyMembers = 2;
  settings.certifyAll = true;
  const Survey survey = surveyScene(build, settings);
  ASSERT_TRUE(survey.limit.empty()) << survey.limit;
  SurveySettings scanOnly = settings;
  scanOnly.certifyMembers = 0;
  const std::vector<Pick> first = pickPerIntegrator(build, survey, scanOnly, error);
  const std::vector<Pick> picks = pickPerIntegrator(build, survey, settings, error);
  int moved = 0;
  for (std::size_t k = 0; k < picks.size(); ++k) {
    const Pick& p = picks[k];
    ASSERT_TRUE(p.found && p.certified()) << p.candidate.integrator << ": " << p.uncertified;
    EXPECT_LE(p.marginError, error) << p.candidate.integrator;
    EXPECT_EQ(p.marginRuns.failures, 0);
    EXPECT_GE(p.marginRuns.runs, 40L * settings.certifyMembers);
    moved += p.candidate.dt < first[k].candidate.dt;
    for (double dt = p.certifiedLo; dt <= p.certifiedHi * (1 + 1e-12); dt *= 1.005) {
      const Candidate c = measureRun(build, *survey.referenceTrajectory, p.candidate.integrator, dt, 0.0, horizon,
                                     settings.failure, survey.energyScale);
      ASSERT_TRUE(c.survived) << p.candidate.integrator << " dt " << dt;
      EXPECT_LE(c.maxError, error) << p.candidate.integrator << " dt " << dt;
    }
  }
  EXPECT_GT(moved, 0) << "every first pick's margin already kept E: the test shows nothing";
}

// The flags of a pick: headroom against E, thin within 5%, and the timing spread behind a tie.
TEST(Advise, HeadroomIsFlaggedWithinFivePercentAndNoisyTiesShowTheirSpread) {
  Pick p;
  p.found = true;
  p.candidate.maxError = 0.9e-3;
  EXPECT_NEAR(headroom(p, 1e-3), 0.1, 1e-12);
  EXPECT_FALSE(thinHeadroom(p, 1e-3));
  p.certifiedLo = 0.1, p.certifiedHi = 0.2, p.worstError = 0.995e-3;  // certified: the worst start counts
  EXPECT_TRUE(thinHeadroom(p, 1e-3));
  std::vector<Pick> picks(3, p);
  picks[0].cpuPerSimulatedSecond = 1.0, picks[0].cpuMin = 0.5, picks[0].cpuMax = 4.0;
  picks[1].cpuPerSimulatedSecond = 1.2, picks[1].cpuMin = 1.1, picks[1].cpuMax = 1.3;
  picks[2].cpuPerSimulatedSecond = 9.0, picks[2].cpuMin = 8.0, picks[2].cpuMax = 10.0;
  markTies(picks, 0);
  const TimingSpread spread = timingSpread(picks, 0);
  EXPECT_EQ(spread.ties, 1);
  EXPECT_NEAR(spread.spread, 8.0, 1e-12);
  EXPECT_EQ(spread.lo, 0.5);
  EXPECT_EQ(spread.hi, 4.0);
}

TEST(Advise, PicksWhoseTimingRangesOverlapTheCheapestAreTies) {
  std::vector<Pick> picks(4);
  const double ranges[4][3] = {{2.0, 1.8, 2.2}, {1.0, 0.9, 1.1}, {1.2, 1.05, 1.3}, {1.5, 1.2, 1.6}};
  for (int k = 0; k < 4; ++k) {
    picks[k].found = true;
    picks[k].cpuPerSimulatedSecond = ranges[k][0], picks[k].cpuMin = ranges[k][1], picks[k].cpuMax = ranges[k][2];
  }
  picks[3].found = false;
  const int best = cheapest(picks);
  ASSERT_EQ(best, 1);
  markTies(picks, best);
  EXPECT_FALSE(picks[0].tie);
  EXPECT_FALSE(picks[1].tie);
  EXPECT_TRUE(picks[2].tie);
  EXPECT_FALSE(picks[3].tie);
}
