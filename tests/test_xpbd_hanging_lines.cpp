// XPBD's hanging lines (xpbd/hanging_lines.h): a pass is the dense solve of
// every line's rows at once, the lines taken are the ones along the holds,
// one pass on a vertical chain is Gauss–Seidel converged, and a stiff
// hanging cloth holds its length with a few substeps.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "particles/constraints/line.h"
#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "integrators/xpbd.h"
#include "particles/particle_system.h"
#include "xpbd/hanging_lines.h"
#include "scenes/cloth.h"

using namespace particles;
using Eigen::Vector2d;

namespace {

// K lines of m constraints, particle (line l, row t) at index l + K t: lines
// 0…K−2 held on slanted rails, line K−1 pinned; masses, rest lengths,
// compliances and the lines' bends vary, and every other constraint's
// particles are listed in reverse. K = 11 gives a bundle of 8 lanes and one of 3.
struct Lines {
  static constexpr int K = 11, m = 6;
  Eigen::VectorXd x, xn, v, mass, w;
  std::vector<CompliantDistance> distances;
  ConstraintList holds;
  int across = 0;  // constraints between neighbouring lines, on none

  Lines() {
    const int n = K * (m + 1);
    x.resize(2 * n);
    xn.resize(2 * n);
    v = Eigen::VectorXd::Zero(2 * n);
    mass.resize(n);
    w.resize(n);
    for (int p = 0; p < n; ++p) {
      const int l = p % K, t = p / K;
      const Vector2d at(1.5 * l + 0.2 * std::sin(1.7 * p), -1.0 * t + 0.15 * std::cos(2.3 * p));
      x.segment<2>(2 * p) = at;
      xn.segment<2>(2 * p) = at - Vector2d(0.01 * std::sin(p), 0.02 * std::cos(3.0 * p));
      mass[p] = 1.0 + 0.37 * ((7 * p) % 5);
      w[p] = 1.0 / mass[p];
    }
    w[K - 1] = 0.0;  // line K − 1 hangs from a pin
    for (int t = 0; t < m; ++t)
      for (int l = 0; l < K; ++l) {
        const int i = l + K * t, j = i + K;
        CompliantDistance c;
        c.i = (i % 2 == 0) ? i : j;
        c.j = (i % 2 == 0) ? j : i;
        c.rest = 0.9 + 0.05 * (t % 3);
        c.compliance = {0.01 * (1 + (i % 3)), (i % 4 == 0) ? 0.0 : 0.2};
        distances.push_back(c);
        if (l + 1 < K && t % 2 == 0) {  // a rung, on no line
          distances.push_back({i, i + 1, 1.5, {0.01, 0.1}});
          ++across;
        }
      }
    for (int l = 0; l + 1 < K; ++l)
      holds.push_back(std::make_unique<LineConstraint>(l, x.segment<2>(2 * l) + Vector2d(0.0, 0.03), 0.1 * l - 0.4));
  }
  Phase phase() const { return {x, v, mass, w}; }
};

// The hold's C and gradient at x from its own kernel.
std::pair<double, Vector2d> holdRow(const Constraint& hold, const Phase& s) {
  Vector2d blocks[2];
  ConstraintRow row;
  row.J = &blocks[0];
  row.Jdot = &blocks[1];
  hold.evaluate(s, row);
  return {row.C, blocks[0]};
}

// Dense: rows (each line's hold, then its constraints), J, and
// (D J W Jᵀ + diag α̃) Δλ = b with D = diag(1 + γ) (1 for a hold),
// b = −C − γ J (x − xⁿ); x + W Jᵀ Δλ.
Eigen::VectorXd denseSolve(const Lines& lines) {
  const int n = static_cast<int>(lines.mass.size());
  std::vector<Eigen::VectorXd> rows;
  std::vector<double> scale, compliance, rhs;
  for (int l = 0; l < Lines::K; ++l) {
    if (l + 1 < Lines::K) {
      const auto [C, g] = holdRow(*lines.holds[static_cast<std::size_t>(l)], lines.phase());
      Eigen::VectorXd row = Eigen::VectorXd::Zero(2 * n);
      row.segment<2>(2 * l) = g;
      rows.push_back(row);
      scale.push_back(1.0);
      compliance.push_back(0.0);
      rhs.push_back(-C);
    }
    for (const CompliantDistance& c : lines.distances) {
      if (c.i % Lines::K != l || c.j % Lines::K != l) continue;
      const Vector2d d = lines.x.segment<2>(2 * c.i) - lines.x.segment<2>(2 * c.j);
      const Vector2d u = d.normalized();
      Eigen::VectorXd row = Eigen::VectorXd::Zero(2 * n);
      row.segment<2>(2 * c.i) = u;
      row.segment<2>(2 * c.j) = -u;
      const double displacement = row.dot(lines.x - lines.xn);
      rows.push_back(row);
      scale.push_back(1.0 + c.compliance.gamma);
      compliance.push_back(c.compliance.alphaTilde);
      rhs.push_back(-(d.norm() - c.rest) - c.compliance.gamma * displacement);
    }
  }
  const int r = static_cast<int>(rows.size());
  Eigen::MatrixXd J(r, 2 * n);
  for (int k = 0; k < r; ++k) J.row(k) = rows[static_cast<std::size_t>(k)].transpose();
  Eigen::VectorXd W(2 * n);
  for (int p = 0; p < n; ++p) W.segment<2>(2 * p).setConstant(lines.w[p]);
  Eigen::MatrixXd A = J * W.asDiagonal() * J.transpose();
  Eigen::VectorXd b(r);
  for (int k = 0; k < r; ++k) {
    A.row(k) *= scale[static_cast<std::size_t>(k)];
    A(k, k) += compliance[static_cast<std::size_t>(k)];
    b[k] = rhs[static_cast<std::size_t>(k)];
  }
  // The pinned line's first row has w = 0 at its hold: its rows stay regular through α̃ > 0.
  const Eigen::VectorXd dl = A.fullPivLu().solve(b);
  return lines.x + W.asDiagonal() * (J.transpose() * dl);
}

double worstStrain(const ParticleSystem& system) {
  double worst = 0.0;
  for (const auto& force : system.forceObjects())
    if (const auto* spring = dynamic_cast<const SpringForce*>(force.get()))
      worst = std::max(worst, std::abs(spring->strain(system.positions())));
  return worst;
}

}  // namespace

TEST(HangingLines, OnePassIsTheDenseSolveOfEveryLineAtOnce) {
  Lines lines;
  HangingLines solver;
  const std::vector<CompliantDistance> left = solver.build(lines.distances, lines.holds, lines.phase());
  EXPECT_EQ(solver.lines(), static_cast<std::size_t>(Lines::K));
  EXPECT_EQ(solver.constraints(), static_cast<std::size_t>(Lines::K * Lines::m));
  EXPECT_EQ(left.size(), static_cast<std::size_t>(lines.across));
  const Eigen::VectorXd expected = denseSolve(lines);
  ASSERT_GT((expected - lines.x).norm(), 0.1);  // the pass has work to do
  Eigen::VectorXd x = lines.x;
  solver.project(lines.xn, x, lines.v, lines.mass, lines.w, 0);
  EXPECT_LE((x - expected).lpNorm<Eigen::Infinity>(), 1e-12);
}

// On the stiff cloth's rail (and on a pinned top row) the lines are its
// columns: the springs along the holds' gradients, not the top row along the
// rail nor a diagonal.
TEST(HangingLines, TakesTheColumnsOfACurtainOnARailOrOnPins) {
  for (bool pinned : {false, true}) {
    scenes::Scene scene = scenes::buildCloth(scenes::stiffClothParams(12));
    ParticleSystem& system = *scene.system;
    ConstraintList none;
    if (pinned)
      for (int c = 0; c < 12; ++c) system.setPinned(c, true);
    const XpbdIntegrator::Forms forms = XpbdIntegrator::positionForms(system, 0.001);
    HangingLines solver;
    const auto left = solver.build(forms.distances, pinned ? none : system.constraints(), system.phase());
    EXPECT_EQ(solver.lines(), 12u) << pinned;
    EXPECT_EQ(solver.constraints(), 12u * 11u) << pinned;
    EXPECT_EQ(left.size() + solver.constraints(), forms.distances.size()) << pinned;
    for (const CompliantDistance& c : left) EXPECT_NE(std::abs(c.j - c.i), 12) << "a column spring left over";
  }
}

// A vertical chain hanging from a particle on a rail, moving vertically: its
// constraints are linear in x there, so one pass of the line solve is the
// substep Gauss–Seidel reaches after thousands of passes.
TEST(Xpbd, OnePassOfAHangingLineIsConvergedGaussSeidelOnAVerticalChain) {
  auto run = [](bool lines, int iterations) {
    ParticleSystem system;
    for (int k = 0; k < 10; ++k) system.addParticle(Vector2d(0.0, -1.05 * k - 0.01 * k * k), 1.0 + 0.3 * (k % 3));
    for (int k = 0; k < 10; ++k) system.setVelocity(k, Vector2d(0.0, 0.2 * std::sin(1.3 * k)));
    system.addConstraint(std::make_unique<LineConstraint>(0, Vector2d::Zero(), 0.0));
    for (int k = 0; k + 1 < 10; ++k) system.addForce(std::make_unique<SpringForce>(k, k + 1, 1.0, 500.0, 0.3));
    system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.8)));
    IntegratorSettings settings;
    settings.xpbd.substeps = 1;
    settings.xpbd.iterations = iterations;
    settings.xpbd.lines = lines;
    auto integrator = makeIntegrator("xpbd", settings);
    const Eigen::VectorXd start = system.positions();
    system.step(*integrator, 0.01);
    return std::make_pair(Eigen::VectorXd(system.positions()), (system.positions() - start).lpNorm<Eigen::Infinity>());
  };
  const auto [gaussSeidel, moved] = run(false, 10000);
  const auto [onePass, unused] = run(true, 1);
  const auto [onePassOfGaussSeidel, unused2] = run(false, 1);
  ASSERT_GT(moved, 1e-3);
  EXPECT_LE((onePass - gaussSeidel).lpNorm<Eigen::Infinity>(), 1e-12);
  EXPECT_GT((onePassOfGaussSeidel - gaussSeidel).lpNorm<Eigen::Infinity>(), 1e-4);  // Gauss–Seidel needs the passes
}

// Where the springs turn, XPBD's converged substep depends on where its
// gradients were taken, so the block and the plain passes, each converged
// (2000 passes equal 1000 to 1e-10), end within 1e-5 m of each other on a
// small cloth released moving, not on the same bits.
TEST(Xpbd, HangingLinesAndGaussSeidelConvergeCloseTogetherOnACloth) {
  auto run = [](bool lines, int iterations) {
    scenes::ClothParams p = scenes::stiffClothParams(6);
    p.stiffness = 2e3;
    scenes::Scene scene = scenes::buildCloth(p);
    for (int k = 0; k < scene.system->size(); ++k) scene.system->setVelocity(k, Vector2d(0.3 * (k % 6), -0.1 * (k / 6)));
    IntegratorSettings settings;
    settings.xpbd.substeps = 1;
    settings.xpbd.iterations = iterations;
    settings.xpbd.lines = lines;
    auto integrator = makeIntegrator("xpbd", settings);
    scene.system->step(*integrator, 0.01);
    return Eigen::VectorXd(scene.system->positions());
  };
  for (bool lines : {false, true}) EXPECT_LE((run(lines, 1000) - run(lines, 2000)).lpNorm<Eigen::Infinity>(), 1e-10);
  EXPECT_LE((run(true, 2000) - run(false, 2000)).lpNorm<Eigen::Infinity>(), 1e-5);
}

// The 128×128 stiff cloth of bench_stiff_cloth at 60 Hz with three substeps
// of one pass: with its columns solved directly every spring stays within
// 0.3 % over 1.5 s; plain Gauss–Seidel at ten substeps passes 10 %.
TEST(Xpbd, StiffClothWithHangingLinesHoldsItsLengthWithThreeSubsteps) {
  auto worst = [](int substeps, bool lines) {
    scenes::Scene scene = scenes::buildCloth(scenes::stiffClothParams(128));
    IntegratorSettings settings;
    settings.xpbd.substeps = substeps;
    settings.xpbd.lines = lines;
    auto integrator = makeIntegrator("xpbd", settings);
    double strain = 0.0;
    for (int frame = 0; frame < 90; ++frame) {
      scene.system->step(*integrator, 1.0 / 60.0);
      strain = std::max(strain, worstStrain(*scene.system));
    }
    EXPECT_TRUE(scene.system->finite());
    return strain;
  };
  const double withLines = worst(3, true);
  EXPECT_LE(withLines, 0.003);
  EXPECT_GT(withLines, 1e-4);  // the cloth is loaded: the bound is not met by standing still
  EXPECT_GT(worst(10, false), 0.10);
}

// Switching the lines on or off between steps rebuilds the forms: the next
// step is the one a fresh integrator with that setting takes.
TEST(Xpbd, SwitchingHangingLinesTakesEffectAtTheNextStep) {
  auto cloth = [] { return scenes::buildCloth(scenes::stiffClothParams(16)); };
  IntegratorSettings on;
  on.xpbd.substeps = 4;
  on.xpbd.lines = true;
  IntegratorSettings off = on;
  off.xpbd.lines = false;
  scenes::Scene switched = cloth(), fresh = cloth();
  auto integrator = makeIntegrator("xpbd", off);
  switched.system->step(*integrator, 1.0 / 60.0);
  integrator->configure(on);
  switched.system->step(*integrator, 1.0 / 60.0);
  auto offThenOn = makeIntegrator("xpbd", off);
  fresh.system->step(*offThenOn, 1.0 / 60.0);
  auto second = makeIntegrator("xpbd", on);
  fresh.system->step(*second, 1.0 / 60.0);
  EXPECT_EQ(switched.system->positions(), fresh.system->positions());
}
