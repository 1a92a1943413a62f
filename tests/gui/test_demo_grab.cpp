// The mouse joint feels alike in every scene: on each number key's scene a
// scripted left drag grabs a particle, holds it, moves the cursor 5 cm and
// holds again, and the particle follows the move to within 10% (the steady
// gap, read from the state log's grab record). Also: --grab, and keys w and t.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "demo_driver.h"
#include "particles/constraints/circular_wire.h"
#include "scene.h"
#include "scene_keys.h"

using namespace demotest;

namespace {

// Frames of the protocol: the scene runs half a second, a press grabs the
// lowest movable particle (the rightmost of equals), the cursor holds still
// for two seconds, moves over 6 frames and holds two seconds more.
constexpr int kPress = 30, kHold = 120, kMove = 6;

struct Move {
  char key;
  const char* name;
  Eigen::Vector2d direction;  // unit; ignored for a bead on a wire, which moves 5 cm along its wire
};

std::ostream& operator<<(std::ostream& out, const Move& m) { return out << "key " << m.key << " " << m.name; }

int lowestMovable(const LoggedPane& pane) {
  int pick = -1;
  for (std::size_t i = 0; i < pane.particles.size(); ++i) {
    const LoggedParticle& q = pane.particles[i];
    if (q.pinned) continue;
    if (pick < 0 || q.x.y() < pane.particles[pick].x.y() ||
        (q.x.y() == pane.particles[pick].x.y() && q.x.x() > pane.particles[pick].x.x()))
      pick = static_cast<int>(i);
  }
  return pick;
}

// The circular wire particle i rides in the key's scene, if any.
const particles::CircularWireConstraint* wireOf(const scenes::Scene& scene, int i) {
  for (const auto& c : scene.system->constraints())
    if (const auto* wire = dynamic_cast<const particles::CircularWireConstraint*>(c.get()))
      if (wire->particles().front() == i) return wire;
  return nullptr;
}

std::string line(long long frame, const char* what, const Eigen::Vector2d& at) {
  std::ostringstream s;
  s.precision(17);
  s << frame << " " << what << " world " << at.x() << " " << at.y() << "\n";
  return s.str();
}

class GrabFeelsAlike : public ::testing::TestWithParam<Move> {};

}  // namespace

TEST_P(GrabFeelsAlike, TheParticleFollowsAFiveCentimetreMoveWithinTenPercent) {
  const Move move = GetParam();
  const std::string dir = outputDirectory(std::string("Grab") + move.key + move.name);
  const std::string options = std::string("--key ") + move.key + " --no-panel ";
  ASSERT_EQ(runDemo(dir, options + "--frames " + std::to_string(kPress) + " --log-state pressed.txt").exitCode, 0);
  const LoggedPane before = readStateLog(dir + "/pressed.txt").panes.at(0);
  const int pick = lowestMovable(before);
  ASSERT_GE(pick, 0);
  const Eigen::Vector2d at = before.particles[pick].x;

  // Zoomed in about the particle (8 wheel clicks, 4.3×) so a pixel is ~1 mm
  // or less, then pressed on it and held.
  std::ostringstream hold;
  hold << kPress - 1 << " wheel world " << at.x() << " " << at.y() << " 8\n" << line(kPress, "down", at);
  ASSERT_EQ(runDemo(dir, options + "--frames " + std::to_string(kPress + kHold) + " --log-state held.txt", hold.str())
                .exitCode, 0);
  const LoggedPane held = readStateLog(dir + "/held.txt").panes.at(0);
  ASSERT_EQ(held.grabs.size(), 1u);
  const LoggedGrab g0 = held.grabs[0];
  ASSERT_EQ(g0.framesAveraged, 60);

  // The cursor's path: 5 cm along the move, or along the bead's wire.
  const scenes::Scene scene = demo::buildChoice([&] {
    for (const demo::SceneKey& k : demo::sceneKeys())
      if (k.key == static_cast<unsigned char>(move.key)) return k.choice;
    return demo::SceneChoice{};
  }());
  const particles::CircularWireConstraint* wire = wireOf(scene, g0.particle);
  const auto cursor = [&](double fraction) -> Eigen::Vector2d {
    if (!wire) return g0.target + 0.05 * fraction * move.direction;
    const Eigen::Vector2d r = g0.target - wire->centre();
    const double angle = std::atan2(r.y(), r.x()) + 0.05 * fraction / wire->radius();
    return wire->centre() + wire->radius() * Eigen::Vector2d(std::cos(angle), std::sin(angle));
  };
  std::string moved = hold.str();
  for (int k = 1; k <= kMove; ++k) moved += line(kPress + kHold + k, "move", cursor(double(k) / kMove));
  const long long end = kPress + 2 * kHold + kMove;
  ASSERT_EQ(runDemo(dir, options + "--frames " + std::to_string(end) + " --log-state moved.txt", moved).exitCode, 0);
  const LoggedPane after = readStateLog(dir + "/moved.txt").panes.at(0);
  ASSERT_EQ(after.grabs.size(), 1u);
  const LoggedGrab g1 = after.grabs[0];
  EXPECT_EQ(g1.particle, g0.particle);
  EXPECT_FALSE(after.diverged);

  const Eigen::Vector2d targetMove = g1.target - g0.target;
  ASSERT_NEAR(targetMove.norm(), 0.05, 0.01) << "the cursor's pixels do not give a 5 cm move";
  const double gap = ((g1.mean - g0.mean) - targetMove).norm() / targetMove.norm();
  std::printf("%c %s: particle %d, k = %.4g N/m, c = %.4g N s/m, steady gap %.2f%% of a %.1f mm move\n", move.key,
              move.name, g0.particle, g0.stiffness, g0.damping, 100.0 * gap, 1000.0 * targetMove.norm());
  EXPECT_LE(gap, 0.10);
}

INSTANTIATE_TEST_SUITE_P(
    EveryScene, GrabFeelsAlike,
    ::testing::Values(Move{'1', "ClothRight", {1, 0}}, Move{'1', "ClothDown", {0, -1}},
                      Move{'2', "Cloth8Right", {1, 0}}, Move{'2', "Cloth8Down", {0, -1}},
                      Move{'3', "HairRight", {1, 0}}, Move{'3', "HairDown", {0, -1}},
                      Move{'4', "WireAlongItsWire", {1, 0}}, Move{'5', "RodChainRight", {1, 0}},
                      Move{'6', "TestChainRight", {1, 0}}, Move{'7', "TautChainRight", {1, 0}},
                      Move{'8', "OscillatorDown", {0, -1}}, Move{'9', "PendulumAlongItsWire", {1, 0}},
                      Move{'0', "StiffClothRight", {1, 0}}, Move{'0', "StiffClothDown", {0, -1}}),
    [](const ::testing::TestParamInfo<Move>& info) { return std::string("Key") + info.param.key + info.param.name; });

namespace {
std::string topBar(const StateLog& log) {
  const LoggedOverlay* top = log.overlay("top-bar");
  return top ? top->text : "";
}
bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }
}  // namespace

// --grab sets the joint: on the oscillator's 1 kg bob (a 40 N/m spring, no
// other tie) a 2 Hz joint with stiffness ratio 0 is k = (2π·2)² = 157.9 N/m,
// c = 2 · 0.5 · 2π·2 = 12.57 N s/m; a bad value is refused in one line.
TEST(DemoGrabOption, SetsTheJointAndABadValueIsRefusedInOneLine) {
  const std::string dir = outputDirectory("GrabOption");
  ASSERT_EQ(runDemo(dir, "--scene oscillator --frames 1 --paused --log-state start.txt").exitCode, 0);
  const Eigen::Vector2d bob = readStateLog(dir + "/start.txt").panes.at(0).particles.at(1).x;
  const RunResult r = runDemo(dir,
                              "--scene oscillator --frames 10 --log-state state.txt --grab frequency=2 "
                              "--grab damping-ratio=0.5 --grab stiffness-ratio=0",
                              line(2, "down", bob));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const LoggedPane pane = readStateLog(dir + "/state.txt").panes.at(0);
  ASSERT_EQ(pane.grabs.size(), 1u);
  const double omega = 2.0 * 3.14159265358979323846 * 2.0;
  EXPECT_NEAR(pane.grabs[0].stiffness, omega * omega, 1e-9);
  EXPECT_NEAR(pane.grabs[0].damping, 2.0 * 0.5 * omega, 1e-9);
  // The default: nine times the spring's 40 N/m is less than the bob's 5 Hz joint, 987 N/m.
  ASSERT_EQ(runDemo(dir, "--scene oscillator --frames 10 --log-state state.txt", line(2, "down", bob)).exitCode, 0);
  EXPECT_NEAR(readStateLog(dir + "/state.txt").panes.at(0).grabs.at(0).stiffness, std::pow(2.0 * 3.14159265358979323846 * 5.0, 2),
              1e-9);
  for (const char* bad : {"frequency=0", "damping-ratio=-1", "stiffness-ratio=nan", "stiffness=3", "frequency"}) {
    SCOPED_TRACE(bad);
    const RunResult refused = runDemo(dir, std::string("--scene oscillator --frames 1 --grab ") + bad);
    EXPECT_EQ(refused.exitCode, 2);
    ASSERT_EQ(refused.errLines().size(), 1u) << refused.err;
    EXPECT_TRUE(contains(refused.err, "--grab")) << refused.err;
  }
}

// w blows the panel's wind (5 m/s to the right, gusts ±50%) on the 4-way
// cloth: after 3 s its particles stand right of where the still cloth's do
// by centimetres; w again stops it. On the pendulum, with no edges, w says so.
TEST(DemoWindKey, BlowsTheClothAndSaysSoWhereNoEdgesCatchIt) {
  const std::string dir = outputDirectory("WindKey");
  const auto meanX = [](const LoggedPane& pane) {
    double sum = 0.0;
    for (const LoggedParticle& q : pane.particles) sum += q.x.x();
    return sum / pane.particles.size();
  };
  ASSERT_EQ(runDemo(dir, "--key 1 --no-panel --frames 180 --log-state still.txt").exitCode, 0);
  ASSERT_EQ(runDemo(dir, "--key 1 --no-panel --frames 180 --log-state windy.txt", "1 key w\n").exitCode, 0);
  const LoggedPane still = readStateLog(dir + "/still.txt").panes.at(0);
  const StateLog windyLog = readStateLog(dir + "/windy.txt");
  const LoggedPane windy = windyLog.panes.at(0);
  EXPECT_EQ(still.wind.speed, 0.0);
  EXPECT_EQ(windy.wind.speed, 5.0);
  EXPECT_GE(windy.wind.air.x(), 2.5);  // within (1 ± 0.5) × 5 m/s, to the right
  EXPECT_LE(windy.wind.air.x(), 7.5);
  EXPECT_GT(meanX(windy) - meanX(still), 0.02) << "the wind did not move the cloth";
  ASSERT_EQ(runDemo(dir, "--key 1 --no-panel --frames 20 --log-state off.txt", "1 key w\n5 key w\n").exitCode, 0);
  EXPECT_EQ(readStateLog(dir + "/off.txt").panes.at(0).wind.speed, 0.0);
  ASSERT_EQ(runDemo(dir, "--key 9 --no-panel --frames 5 --log-state none.txt", "1 key w\n").exitCode, 0);
  EXPECT_TRUE(contains(topBar(readStateLog(dir + "/none.txt")), "no edges")) << topBar(readStateLog(dir + "/none.txt"));
}

// t turns tearing on (strain 0.5); the hem's corner pulled 40 cm down and
// out tears springs, while the same pull without t tears none.
TEST(DemoTearKey, APullTearsTheClothOnlyWithTearingOn) {
  const std::string dir = outputDirectory("TearKey");
  ASSERT_EQ(runDemo(dir, "--key 1 --no-panel --frames 1 --paused --log-state start.txt").exitCode, 0);
  const LoggedPane start = readStateLog(dir + "/start.txt").panes.at(0);
  const Eigen::Vector2d corner = start.particles.at(lowestMovable(start)).x;
  std::string pull = line(2, "down", corner);
  for (int k = 1; k <= 30; ++k) pull += line(2 + k, "move", corner + Eigen::Vector2d(0.15, -0.4) * (k / 30.0));
  ASSERT_EQ(runDemo(dir, "--key 1 --no-panel --frames 90 --log-state intact.txt", pull).exitCode, 0);
  ASSERT_EQ(runDemo(dir, "--key 1 --no-panel --frames 90 --log-state torn.txt", "1 key t\n" + pull).exitCode, 0);
  const LoggedPane intact = readStateLog(dir + "/intact.txt").panes.at(0);
  const LoggedPane torn = readStateLog(dir + "/torn.txt").panes.at(0);
  EXPECT_EQ(intact.tearStrain, 0.0);
  EXPECT_EQ(intact.brokenLinks, 0);
  EXPECT_EQ(torn.tearStrain, 0.5);
  EXPECT_GT(torn.brokenLinks, 0);
}
