// `particle-lab claims`: the seed report's claims, each confirmed or refuted by
// a measurement.
#include <cmath>
#include <limits>

#include "lab/chain.h"
#include "lab/experiments.h"
#include "particles/forces/mouse_spring.h"

namespace lab {

namespace {

// Mean and largest |corner angle − 90°| (degrees) over the cells of a cloth
// whose particles are laid out row by row, `width` per row.
std::pair<double, double> cellShear(const particles::ParticleSystem& s, int width, int height) {
  double sum = 0.0, worst = 0.0;
  int cells = 0;
  for (int r = 0; r + 1 < height; ++r)
    for (int c = 0; c + 1 < width; ++c) {
      const int i = r * width + c;
      const Eigen::Vector2d a = s.position(i + 1) - s.position(i), b = s.position(i + width) - s.position(i);
      const double cosine = a.dot(b) / (a.norm() * b.norm());
      const double shear = std::abs(std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / M_PI - 90.0);
      sum += shear, worst = std::max(worst, shear), ++cells;
    }
  return {cells ? sum / cells : 0.0, worst};
}

std::string verdict(bool confirmed) { return confirmed ? "confirmed" : "refuted"; }

}  // namespace

int runClaims(const LabOptions& options) {
  prepareOutput(options);
  const bool q = options.quick;
  const Explosion explosion;
  Progress progress("claims", q ? 30 : 80);
  std::vector<std::vector<std::string>> table;
  const TimingOptions timing{q ? 1 : 5, q ? 5 : 20};
  const int chainLength = q ? 12 : 80;

  // 1. "Changing the time step size has virtually no effect on the duration of the time step."
  {
    Csv csv(options.outDir + "/claims_cost_vs_dt.csv", {"integrator", "dt", "step_seconds", "cg_iterations_per_step"});
    double worstRatio = 0.0;
    for (const std::string name : {"midpoint", "rk4"}) {
      double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
      for (double dt : {0.005, 0.01, 0.02, 0.05, 0.1}) {
        scenes::Scene chain = buildChain({chainLength});
        const StepCost cost = measureStepCost(chain, name, dt, timing);
        csv << name << dt << cost.seconds << cost.cgIterations;
        csv.endRow();
        if (std::isfinite(cost.seconds)) lo = std::min(lo, cost.seconds), hi = std::max(hi, cost.seconds);
        progress.tick();
      }
      worstRatio = std::max(worstRatio, hi / lo);
    }
    recordValue(options, "claims.cost_vs_dt_ratio", fixed(worstRatio, 2));
    table.push_back({"cost per step hardly depends on dt",
                     "slowest/fastest step over dt 0.005–0.1 (midpoint, RK4, " + std::to_string(chainLength) +
                         "-chain): " + fixed(worstRatio, 2),
                     verdict(worstRatio < 1.5)});
  }

  // 2. "RK4 is about twice as slow as midpoint, but allows more than twice the step."
  {
    scenes::Scene a = buildChain({chainLength}), b = buildChain({chainLength});
    const double rk4 = measureStepCost(a, "rk4", a.dt, timing).seconds;
    const double mid = measureStepCost(b, "midpoint", b.dt, timing).seconds;
    const int cl = q ? 6 : 24;
    const double duration = q ? 2.0 : 20.0;
    auto maxStep = [&](const std::string& name) {
      return maxStableStep([&] { return buildChain({cl}); }, name, duration, 1e-3, 0.5, q ? 4 : 8, explosion,
                           progress);
    };
    const double dtRk4 = maxStep("rk4"), dtMid = maxStep("midpoint");
    recordValue(options, "claims.rk4_midpoint_cost_ratio", fixed(rk4 / mid, 2));
    recordValue(options, "claims.rk4_midpoint_step_ratio", fixed(dtRk4 / dtMid, 2));
    table.push_back({"RK4 costs about twice midpoint per step",
                     "RK4/midpoint step time: " + fixed(rk4 / mid, 2), verdict(rk4 / mid > 1.5 && rk4 / mid < 2.5)});
    table.push_back({"RK4 allows more than twice midpoint's step",
                     "largest stable dt, " + std::to_string(cl) + "-chain, T = " + general(duration) +
                         " s: RK4 " + general(dtRk4, 3) + ", midpoint " + general(dtMid, 3) + " (ratio " +
                         fixed(dtRk4 / dtMid, 2) + ")",
                     verdict(dtRk4 > 2.0 * dtMid)});
  }

  // 3. "The number of CG steps is about linear in the number of constraints."
  {
    Csv csv(options.outDir + "/claims_cg_iterations.csv",
            {"constraints", "plain_cg_iterations_per_solve", "jacobi_warm_cg_iterations_per_solve"});
    const std::vector<int> lengths = q ? std::vector<int>{5, 10, 20} : std::vector<int>{10, 20, 40, 80, 160, 320, 500};
    std::vector<double> m, plain;
    for (int cl : lengths) {
      scenes::Scene chain = buildChain({cl});
      auto& settings = chain.system->solver().settings;
      settings.method = particles::SolveMethod::ConjugateGradient;
      settings.warmStart = false;
      settings.preconditioner = particles::Preconditioner::None;
      const StepCost plainCost = measureStepCost(chain, "rk4", chain.dt, {1, 5});
      scenes::Scene tuned = buildChain({cl});
      tuned.system->solver().settings.method = particles::SolveMethod::ConjugateGradient;
      const StepCost defaultCost = measureStepCost(tuned, "rk4", tuned.dt, {1, 5});
      const double constraints = static_cast<double>(chain.system->constraints().size());
      csv << constraints << plainCost.cgIterationsPerSolve() << defaultCost.cgIterationsPerSolve();
      csv.endRow();
      m.push_back(constraints), plain.push_back(plainCost.cgIterationsPerSolve());
      progress.tick();
    }
    const double slope = logLogSlope(m, plain);
    recordValue(options, "claims.cg_iterations_slope", fixed(slope, 2));
    table.push_back({"CG iterations grow about linearly with the number of constraints",
                     "plain CG iterations per solve ∝ m^" + fixed(slope, 2) + " (chains of " +
                         std::to_string(lengths.front()) + "–" + std::to_string(lengths.back()) + ")",
                     verdict(slope > 0.8 && slope < 1.2)});
  }

  // 4. "A solver limited below the desired number of steps stretches rods but does not explode."
  //    Jacobi CG capped at a few iterations, started cold and warm (from the
  //    previous λ, which lets a capped solve keep converging across steps).
  {
    std::string detail;
    bool survived[2] = {true, true};
    for (bool warm : {false, true}) {
      detail += std::string(detail.empty() ? "" : "; ") + (warm ? "warm start:" : "cold start:");
      for (int cap : {1, 2, 5, 0}) {
        scenes::Scene chain = buildChain({chainLength});
        auto& settings = chain.system->solver().settings;
        settings.method = particles::SolveMethod::ConjugateGradient;
        settings.maxIterations = cap;
        settings.warmStart = warm;
        auto stepper = particles::makeIntegrator("rk4");
        const RunResult r = simulate(chain, *stepper, 0.01, q ? 1.0 : 20.0, explosion);
        if (cap > 0) survived[warm] = survived[warm] && !r.exploded;
        detail += std::string(" ") + (cap ? "cap " + std::to_string(cap) : std::string("uncapped")) + " " +
                  (r.exploded ? "exploded (" + r.reason + ")" : "stretch " + general(r.maxRelativeStretch, 2));
        progress.tick();
      }
    }
    const std::string outcome = survived[0] && survived[1] ? "confirmed"
                                : survived[1]              ? "confirmed only with warm start"
                                : survived[0]              ? "confirmed only with cold start"
                                                           : "refuted";
    table.push_back({"a starved solver stretches rods but does not explode", detail, outcome});
  }

  // 5. "The 4-way cloth under gravity or pulling is less cloth-like than the 8-way one": cell shear.
  {
    Csv csv(options.outDir + "/claims_cloth_shear.csv", {"links", "mean_shear_degrees", "max_shear_degrees"});
    const int side = q ? 5 : 10;
    double mean[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
      const std::string links = k == 0 ? "4" : "8";
      scenes::Scene cloth = scenes::buildScene(
          "cloth", {{"width", std::to_string(side)}, {"height", std::to_string(side)}, {"links", links}},
          scenes::kSeedPreset);
      // Pull the bottom-left corner sideways, as a user dragging it would.
      const int corner = (side - 1) * side;
      cloth.system->addForce(std::make_unique<particles::MouseSpringForce>(
          corner, cloth.system->position(corner) + Eigen::Vector2d(-0.3, 0.0), 1.0, 0.5));
      auto stepper = particles::makeIntegrator("rk4");
      double sum = 0.0, worst = 0.0;
      int samples = 0;
      simulate(cloth, *stepper, cloth.dt, q ? 2.0 : 20.0, explosion, [&](const particles::ParticleSystem& s) {
        const auto [m, w] = cellShear(s, side, side);
        sum += m, worst = std::max(worst, w), ++samples;
      });
      mean[k] = samples ? sum / samples : 0.0;
      csv << links << mean[k] << worst;
      csv.endRow();
      progress.tick();
    }
    recordValue(options, "claims.shear_4way", fixed(mean[0], 2));
    recordValue(options, "claims.shear_8way", fixed(mean[1], 2));
    table.push_back({"4-way cloth deforms less cloth-like than 8-way",
                     "mean cell shear while pulled: 4-way " + fixed(mean[0], 1) + "°, 8-way " + fixed(mean[1], 1) + "°",
                     verdict(mean[0] > mean[1])});
  }

  writeTable(options, "claims", "The seed report's claims, measured", {"claim", "measurement", "verdict"}, table);
  return interrupted() ? 130 : 0;
}

}  // namespace lab
