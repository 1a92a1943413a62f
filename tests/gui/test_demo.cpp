// particle-demo under Xvfb: runs the program with scripted input and checks
// its exit code, its state log and its screenshots.
#include <cstdio>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

#include "demo_driver.h"
#include "particles/integrator.h"
#include "scene.h"
#include "scene_file/scene_file.h"
#include "scene_keys.h"
#include "scenes/cloth.h"

using namespace demotest;

namespace {

const char* const noPanel = "--no-panel --window 900x700";

// Pixels (columns, rows) where a particle of pane p is drawn: the particle's
// colour must appear within a pixel of its mapped position.
int particlesDrawn(const Image& image, const StateLog& log, const LoggedPane& p, int* checked) {
  int drawn = 0;
  *checked = 0;
  for (const LoggedParticle& q : p.particles) {
    const Eigen::Vector2d px = p.toPixel(q.x);
    if (log.underOverlay(px, 4)) continue;
    if (px.x() < p.pixelX + 2 || px.y() < p.pixelY + 2 || px.x() > p.pixelX + p.pixelWidth - 3 ||
        px.y() > p.pixelY + p.pixelHeight - 3)
      continue;
    ++*checked;
    const demo::Rgb expected = q.pinned ? demo::palette::pinnedParticle : demo::palette::particle;
    bool found = false;
    for (int dy = -1; dy <= 1 && !found; ++dy)
      for (int dx = -1; dx <= 1 && !found; ++dx)
        found = near(image.at(static_cast<int>(px.x()) + dx, static_cast<int>(px.y()) + dy), expected, 12);
    drawn += found;
  }
  return drawn;
}

// Pixels of pane p well away from every particle (and the springs between
// them), wall and the HUD: where only the background may be drawn.
std::vector<Eigen::Vector2i> emptyPixels(const StateLog& log, const LoggedPane& p) {
  Eigen::Vector2d lo(1e9, 1e9), hi(-1e9, -1e9);
  for (const LoggedParticle& q : p.particles) {
    lo = lo.cwiseMin(p.toPixel(q.x));
    hi = hi.cwiseMax(p.toPixel(q.x));
  }
  std::vector<Eigen::Vector2i> result;
  for (int y = p.pixelY + 4; y < p.pixelY + p.pixelHeight - 4; y += 12)
    for (int x = p.pixelX + 4; x < p.pixelX + p.pixelWidth - 4; x += 12) {
      const Eigen::Vector2d px(x, y);
      if (log.underOverlay(px)) continue;
      if (px.x() > lo.x() - 24 && px.x() < hi.x() + 24 && px.y() > lo.y() - 24 && px.y() < hi.y() + 24) continue;
      bool inWall = false;
      for (const LoggedWall& w : p.walls) {
        const Eigen::Vector2d a = p.toPixel({w.min.x(), w.max.y()}), b = p.toPixel({w.max.x(), w.min.y()});
        inWall |= px.x() > a.x() - 4 && px.x() < b.x() + 4 && px.y() > a.y() - 4 && px.y() < b.y() + 4;
      }
      if (!inWall) result.push_back({x, y});
    }
  return result;
}

int countNear(const Image& image, demo::Rgb colour, int tolerance, int x0, int y0, int x1, int y1) {
  int count = 0;
  for (int y = std::max(0, y0); y < std::min(image.height, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(image.width, x1); ++x) count += near(image.at(x, y), colour, tolerance);
  return count;
}

double distance(const LoggedParticle& a, const LoggedParticle& b) { return (a.x - b.x).norm(); }

}  // namespace

// ---------------------------------------------------------------------------
// Command line

TEST(DemoCommandLine, BadValuesExitTwoWithOneLine) {
  const std::string dir = outputDirectory("BadValues");
  std::ofstream(dir + "/bad-script.txt") << "0 key r\n5 jump world 0 0\n";
  const std::vector<std::string> cases = {
      "--scene no-such-scene",     "--integrator no-such-integrator", "--dt -1",  "--dt 0", "--dt nan", "--tolerance -1", "--tolerance nan",
      "--dt abc",                  "--frames 0",                      "--frames x",
      "--param links=3",           "--param nosuch=1",                "--param links",  "--preset slow",
      "--compare euler",           "--compare euler,nosuch", "--compare rk4:0,rk4", "--compare rk4:x,euler",          "--window 10x10",
      "--script missing.txt",      "--script bad-script.txt",         "--no-such-option",
      "--scene-file missing.json",      "--scene-file " MALFORMED_DIR "/nan.json",
      "--scene-file " MALFORMED_DIR "/unknown-type.json", "--scene cloth --scene-file " SCENES_DIR "/rod.json",
  };
  for (const std::string& args : cases) {
    SCOPED_TRACE(args);
    const RunResult r = runDemo(dir, args);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(r.out.empty()) << r.out;
    ASSERT_EQ(r.errLines().size(), 1u) << r.err;
    EXPECT_EQ(r.errLines()[0].rfind("particle-demo: ", 0), 0u) << r.err;
  }
}

TEST(DemoCommandLine, MessagesMatchParticleLabs) {
  const std::string dir = outputDirectory("Messages");
  EXPECT_EQ(runDemo(dir, "--dt nan").err, "particle-demo: --dt: value must be > 0, got nan\n");
  EXPECT_EQ(runDemo(dir, "--dt 0").err, "particle-demo: --dt: value must be > 0, got 0\n");
  EXPECT_EQ(runDemo(dir, "--tolerance 0").err, "particle-demo: --tolerance: integrator tolerance must be > 0, got 0\n");
  EXPECT_NE(runDemo(dir, "--scene clot").err.find("particle-demo: unknown scene 'clot' (valid: cloth, hair"),
            std::string::npos);
  EXPECT_EQ(runDemo(dir, "--preset slow").err, "particle-demo: unknown preset 'slow' (valid: default, seed)\n");
  std::string names;
  for (const particles::IntegratorInfo& info : particles::integratorTable())
    names += (names.empty() ? "" : ", ") + std::string(info.name);
  EXPECT_EQ(runDemo(dir, "--integrator rk5").err, "particle-demo: --integrator: unknown integrator 'rk5' (valid: " + names + ")\n");
}

TEST(DemoCommandLine, MalformedSceneFileNamesTheFileAndTheJsonPath) {
  const std::string dir = outputDirectory("MalformedSceneFile");
  const RunResult r = runDemo(dir, "--scene-file " MALFORMED_DIR "/non-positive-mass.json");
  EXPECT_EQ(r.exitCode, 2);
  ASSERT_EQ(r.errLines().size(), 1u) << r.err;
  EXPECT_NE(r.err.find("non-positive-mass.json: $.particles[1].mass: expected a number > 0, got 0"), std::string::npos)
      << r.err;
}

TEST(DemoCommandLine, SceneFileRuns) {
  const std::string dir = outputDirectory("SceneFile");
  const RunResult r = runDemo(dir, "--scene-file " SCENES_DIR "/rod.json --frames 30 --log-state state.txt");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const StateLog log = readStateLog(dir + "/state.txt");
  EXPECT_EQ(log.panes.at(0).scene, "rod.json");
  EXPECT_GT(log.panes.at(0).steps, 0);
  EXPECT_FALSE(log.panes.at(0).particles.empty());
}

// The demo's --scene, --preset, --param and --scene-file are particle-lab's:
// each scene given so starts as the runner builds it (particle-lab export
// writes that scene, read back here), particle by particle, with its dt and
// integrator.
TEST(DemoCommandLine, SceneOptionsBuildTheScenesParticleLabBuilds) {
  const std::string dir = outputDirectory("SceneOptionsAsRunner");
  const std::vector<std::string> cases = {
      "--scene pendulum --preset seed",
      "--scene test-chain --param cl=5 --param length=0.8",
      "--scene test-chain --preset seed --param cl=7",
      "--scene cloth --param links=8 --param width=5 --param height=4",
      "--scene-file " SCENES_DIR "/rod.json",
  };
  for (const std::string& args : cases) {
    SCOPED_TRACE(args);
    const RunResult lab = runParticleLab(dir, "export " + args + " -o scene.json");
    ASSERT_EQ(lab.exitCode, 0) << lab.err;
    const scenes::Scene scene = scenes::loadSceneFile(dir + "/scene.json");
    const RunResult r = runDemo(dir, args + " --paused --frames 1 --no-panel --log-state state.txt");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const StateLog log = readStateLog(dir + "/state.txt");
    const LoggedPane& pane = log.panes.at(0);
    EXPECT_EQ(pane.steps, 0);
    EXPECT_EQ(pane.integrator, scene.integrator);
    EXPECT_DOUBLE_EQ(pane.dt, scene.dt);
    const particles::ParticleSystem& s = *scene.system;
    ASSERT_EQ(pane.particles.size(), static_cast<std::size_t>(s.size()));
    for (int i = 0; i < s.size(); ++i) {
      EXPECT_LT((pane.particles[i].x - s.position(i)).norm(), 1e-12) << "particle " << i;
      EXPECT_LT((pane.particles[i].v - s.velocity(i)).norm(), 1e-12) << "particle " << i;
      EXPECT_DOUBLE_EQ(pane.particles[i].mass, s.masses()[i]) << "particle " << i;
      EXPECT_EQ(pane.particles[i].pinned, s.pinned(i)) << "particle " << i;
    }
  }
}

// A bad scene option is refused by the demo with particle-lab's own line.
TEST(DemoCommandLine, BadSceneOptionsGetParticleLabsMessages) {
  const std::string dir = outputDirectory("SceneOptionMessages");
  const std::string rod = SCENES_DIR "/rod.json";
  const std::vector<std::string> cases = {
      "--scene clot",
      "--scene cloth --preset slow",
      "--scene cloth --param links",
      "--scene cloth --param =4",
      "--scene cloth --param colour=red",
      "--scene cloth --param links=6",
      "--scene test-chain --param cl=many",
      "--scene cloth --scene-file " + rod,
      "--scene-file " + rod + " --preset seed",
      "--scene-file " + rod + " --param links=8",
      "--scene-file missing.json",
      "--scene-file " MALFORMED_DIR "/nan.json",
      "--scene-file /dev/zero",
  };
  for (const std::string& args : cases) {
    SCOPED_TRACE(args);
    const RunResult lab = runParticleLab(dir, "export " + args + " -o scene.json");
    const RunResult demo = runDemo(dir, args + " --frames 1");
    EXPECT_EQ(lab.exitCode, 2);
    EXPECT_EQ(demo.exitCode, 2);
    ASSERT_EQ(lab.errLines().size(), 1u) << lab.err;
    ASSERT_EQ(demo.errLines().size(), 1u) << demo.err;
    const std::string labPrefix = "particle-lab: ", demoPrefix = "particle-demo: ";
    ASSERT_EQ(lab.err.rfind(labPrefix, 0), 0u) << lab.err;
    ASSERT_EQ(demo.err.rfind(demoPrefix, 0), 0u) << demo.err;
    EXPECT_EQ(demo.err.substr(demoPrefix.size()), lab.err.substr(labPrefix.size()));
  }
}

// --compare is read by CLI11: 2 to 4 comma-separated entries, each an
// integrator of the table with an optional dt that is a finite number > 0.
TEST(DemoCommandLine, BadCompareValuesAreNamedInOneLine) {
  const std::string dir = outputDirectory("BadCompare");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"rk4:x,euler", "--compare: dt in 'rk4:x': expected a decimal number, got 'x'"},
      {"rk4:0.01s,euler", "--compare: dt in 'rk4:0.01s': expected a decimal number, got '0.01s'"},
      {"rk4:0x1p-8,euler", "--compare: dt in 'rk4:0x1p-8': expected a decimal number, got '0x1p-8'"},
      {"rk4:1e-3000,euler", "--compare: dt in 'rk4:1e-3000': '1e-3000' is too small for a double: it would read as 0"},
      {"rk4:-0.01,euler", "--compare: dt in 'rk4:-0.01' must be a finite number > 0"},
      {"rk4:inf,euler", "--compare: dt in 'rk4:inf' must be a finite number > 0"},
      {"rk4:nan,euler", "--compare: dt in 'rk4:nan' must be a finite number > 0"},
      {"rk4:,euler", "--compare: dt in 'rk4:': expected a decimal number, got ''"},
      {"euler,rk5", "--compare: unknown integrator 'rk5' (valid: euler, "},
      {":0.01,euler", "--compare: unknown integrator '' (valid: euler, "},
      {"euler", "--compare: "},
      {"euler,rk4,midpoint,verlet,dopri5", "--compare: "},
  };
  for (const auto& [value, message] : cases) {
    SCOPED_TRACE(value);
    const RunResult r = runDemo(dir, "--compare '" + value + "' --frames 1");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(r.out.empty()) << r.out;
    ASSERT_EQ(r.errLines().size(), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("particle-demo: " + message, 0), 0u) << r.err;
  }
  // The same entries, well formed, start one pane each with that integrator and dt.
  const RunResult r = runDemo(dir, "--scene pendulum --compare rk4:0.004,euler,midpoint:0.02 --paused --frames 1 "
                                   "--no-panel --log-state state.txt");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const StateLog log = readStateLog(dir + "/state.txt");
  ASSERT_EQ(log.panes.size(), 3u);
  EXPECT_EQ(log.panes[0].integrator, "rk4");
  EXPECT_DOUBLE_EQ(log.panes[0].dt, 0.004);
  EXPECT_EQ(log.panes[1].integrator, "euler");
  EXPECT_DOUBLE_EQ(log.panes[1].dt, scenes::buildScene("pendulum").dt);
  EXPECT_EQ(log.panes[2].integrator, "midpoint");
  EXPECT_DOUBLE_EQ(log.panes[2].dt, 0.02);
}

// ---------------------------------------------------------------------------
// Keys

TEST(DemoKeys, EveryScenePlusEveryIntegratorByKeyThenQuitExitsZero) {
  const std::string dir = outputDirectory("Keys");
  const int integrators = static_cast<int>(particles::integratorTable().size());
  const std::vector<demo::SceneKey> keys = demo::sceneKeys();
  ASSERT_GE(keys.size(), 8u);
  for (const demo::SceneKey& key : keys) {
    SCOPED_TRACE(key.choice.label);
    // The scene's key, then i through every integrator and back, the other
    // toggles, and q: the run ends on q, not on --frames.
    std::ostringstream script;
    script << "0 key " << key.key << "\n";
    for (int k = 1; k <= integrators; ++k) script << 2 * k << " key i\n";
    script << "12 key f\n13 key c\n14 key h\n15 key v\n16 key v\n17 key v\n18 key v\n20 key q\n";
    const RunResult r = runDemo(dir, "--frames 500 --log-state state.txt", script.str());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
    const StateLog log = readStateLog(dir + "/state.txt");
    EXPECT_EQ(log.frames, 21);  // frames 0..20: q ends the run after drawing frame 20
    ASSERT_EQ(log.panes.size(), 1u);  // v four times: 2, 3, 4 panes, then 1
    EXPECT_EQ(log.panes[0].scene, key.choice.label);
    EXPECT_EQ(log.panes[0].integrator, demo::buildChoice(key.choice).integrator);
    EXPECT_GT(log.panes[0].steps, 0);
    EXPECT_NE(log.overlay("help"), nullptr);    // h shows the help overlay
    ASSERT_NE(log.overlay("hud"), nullptr);     // f adds the force legend to the bottom bar
    EXPECT_NE(log.overlay("hud")->text.find("arrows:"), std::string::npos) << log.overlay("hud")->text;
    EXPECT_NE(log.overlay("hud")->text.find(" --> "), std::string::npos) << log.overlay("hud")->text;
  }
}

namespace {
// The worst strain |ℓ/r − 1| over the n×n grid's 8-way springs in a logged pane.
double worstGridStrain(const LoggedPane& pane, int n) {
  const double rest = scenes::stiffClothParams(n).rest;
  double worst = 0.0;
  auto spring = [&](int a, int b, double r) {
    const double length = (pane.particles[a].x - pane.particles[b].x).norm();
    worst = std::max(worst, std::abs(length / r - 1.0));
  };
  for (int row = 0; row < n; ++row)
    for (int col = 0; col < n; ++col) {
      const int id = row * n + col;
      if (col + 1 < n) spring(id, id + 1, rest);
      if (row + 1 < n) spring(id, id + n, rest);
      if (row + 1 < n && col + 1 < n) {
        spring(id, id + n + 1, std::sqrt(2.0) * rest);
        spring(id + 1, id + n, std::sqrt(2.0) * rest);
      }
    }
  return worst;
}
}  // namespace

// The stiff 64×64 cloth (k_s = 4e5, 8-way springs, scenes::stiffClothParams)
// paired with xpbd at 1/60 s and its hanging lines solved, started by --key 0
// and by pressing 0 (xpbd's settings come with the scene's integrator): after
// a simulated second of hanging loaded, every spring of the grid is within
// 0.3 % of its rest length (Gauss–Seidel alone leaves 2 %; frame times:
// scripts/demo-frame-times.sh).
TEST(DemoKeys, KeyZeroRunsTheStiffClothWithXpbdAt60HzWithinItsStrainBound) {
  // One thread: on a loaded machine a step whose threads wait for each other
  // can pass the frame's stepping budget, and the top bar then says so instead of the hint.
  const std::pair<const char*, const char*> starts[] = {{"--key 0 --frames 60 --threads 1", ""},
                                                        {"--key 1 --frames 61 --threads 1", "1 key 0\n"}};
  for (const auto& [args, script] : starts) {
    SCOPED_TRACE(args);
    const std::string dir = outputDirectory("StiffCloth");
    const RunResult r = runDemo(dir, std::string(args) + " --log-state state.txt", script);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
    const StateLog log = readStateLog(dir + "/state.txt");
    ASSERT_EQ(log.panes.size(), 1u);
    const LoggedPane& pane = log.panes[0];
    EXPECT_EQ(pane.integrator, "xpbd");
    EXPECT_DOUBLE_EQ(pane.dt, 1.0 / 60.0);
    EXPECT_GE(pane.time, 0.9);  // about one simulated second
    EXPECT_FALSE(pane.diverged);
    // Its own hint: what holds its springs, not the soft cloth's nail hint.
    const std::string top = std::regex_replace(log.overlay("top-bar")->text, std::regex(" \\| "), " ");
    if (top.find("stepping budget") == std::string::npos) {  // a step the machine held up shows no hint
      EXPECT_NE(top.find("xpbd at 60 Hz holds every spring within 0.1 %"), std::string::npos) << top;
    }
    EXPECT_EQ(top.find("onto the nail"), std::string::npos) << top;
    // The HUD's threads: the last step's and the most (--threads 1).
    ASSERT_NE(log.overlay("hud"), nullptr);
    EXPECT_NE(log.overlay("hud")->text.find("threads 1/1"), std::string::npos) << log.overlay("hud")->text;
    EXPECT_LE(worstGridStrain(pane, 64), 0.003);
    EXPECT_GT(worstGridStrain(pane, 64), 1e-4);  // loaded: the bound is not met by standing still
  }
}

TEST(DemoKeys, AnUnknownSceneKeyIsRefusedInOneLine) {
  const RunResult r = runDemo(outputDirectory("BadKey"), "--key x --frames 1");
  EXPECT_EQ(r.exitCode, 2);
  ASSERT_EQ(r.errLines().size(), 1u) << r.err;
  EXPECT_NE(r.err.find("--key expects one of"), std::string::npos) << r.err;
}

TEST(DemoKeys, IntegratorKeyKeepsTheState) {
  const std::string dir = outputDirectory("IntegratorKeepsState");
  // Paused: i must change the integrator and nothing else.
  runDemo(dir, "--scene test-chain --frames 30 --log-state before.txt", "");
  const RunResult r = runDemo(dir, "--scene test-chain --frames 31 --log-state after.txt", "30 key space\n30 key i\n");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const StateLog before = readStateLog(dir + "/before.txt"), after = readStateLog(dir + "/after.txt");
  EXPECT_NE(before.panes[0].integrator, after.panes[0].integrator);
  EXPECT_EQ(before.panes[0].time, after.panes[0].time);
  for (std::size_t i = 0; i < before.panes[0].particles.size(); ++i)
    EXPECT_EQ(before.panes[0].particles[i].x, after.panes[0].particles[i].x);
}

TEST(DemoKeys, DtKeysDoubleAndHalve) {
  const std::string dir = outputDirectory("DtKeys");
  const RunResult r = runDemo(dir, "--scene pendulum --dt 0.01 --frames 5 --log-state state.txt",
                              "1 key +\n2 key +\n3 key -\n");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_DOUBLE_EQ(readStateLog(dir + "/state.txt").panes[0].dt, 0.02);
}

// ---------------------------------------------------------------------------
// Frame-rate independence: a fixed simulated time per frame

TEST(DemoStepping, FixedSimulatedTimePerFrameAndLockstep) {
  const std::string dir = outputDirectory("Stepping");
  ASSERT_EQ(runDemo(dir, "--scene pendulum --dt 0.005 --frames 60 --log-state fixed.txt").exitCode, 0);
  ASSERT_EQ(runDemo(dir, "--scene pendulum --dt 0.005 --frames 60 --lockstep --log-state lockstep.txt").exitCode, 0);
  EXPECT_NEAR(readStateLog(dir + "/fixed.txt").panes[0].time, 1.0, 1e-9);  // 60 frames of 1/60 s
  EXPECT_EQ(readStateLog(dir + "/fixed.txt").panes[0].steps, 200);
  EXPECT_EQ(readStateLog(dir + "/lockstep.txt").panes[0].steps, 60);
}

TEST(DemoStepping, RealtimeFramesComeFromTheSixtyHertzClock) {
  // The interactive frame clock: 60 frames cannot take less than about a
  // second (only a lower bound; a slow machine may take longer), and simulate 1 s.
  const std::string dir = outputDirectory("Realtime");
  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(runDemo(dir, "--scene pendulum --frames 60 --realtime --log-state state.txt").exitCode, 0);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GT(seconds, 0.9);
  EXPECT_NEAR(readStateLog(dir + "/state.txt").panes.at(0).time, 1.0, 1e-9);
}

TEST(DemoStepping, RealTimeReadoutIsTheLoggedRatioAndSlowMotionIsSaidBelowIt) {
  // The HUD's "x real time" is simulated over wall seconds of the last second
  // of frames: the readout shown is the logged ratio to two decimals, the
  // logged simulated seconds are the frames' (every frame advances 1/60 s),
  // and the state line says slow motion exactly when a paced run's ratio is
  // below 0.95. No bound on the ratio itself: it depends on the machine.
  const std::string dir = outputDirectory("RealTimeReadout");
  for (const char* pacing : {"--realtime", ""}) {
    const std::string name = std::string("state") + pacing + ".txt";
    ASSERT_EQ(runDemo(dir, std::string("--scene pendulum --frames 90 ") + pacing + " --log-state " + name).exitCode, 0);
    const StateLog log = readStateLog(dir + "/" + name);
    EXPECT_EQ(log.realTimePaced, std::string(pacing) == "--realtime");
    // the first frame starts the clock; whole steps of dt 0.005 s reach the frames' times
    EXPECT_NEAR(log.realTimeSimSeconds, 89.0 / 60.0, 0.005);
    EXPECT_GT(log.realTimeWallSeconds, 0.0);
    ASSERT_GT(log.realTimeLastSecond, 0.0);
    char readout[64];
    std::snprintf(readout, sizeof readout, "%.2fx real time", log.realTimeLastSecond);
    const LoggedOverlay* hud = log.overlay("hud");
    ASSERT_NE(hud, nullptr);
    EXPECT_NE(hud->text.find(readout), std::string::npos) << hud->text;
    const bool slow = log.realTimePaced && log.realTimeLastSecond < 0.95;
    EXPECT_EQ(hud->text.find("slow motion") != std::string::npos, slow) << hud->text;
    if (!log.realTimePaced) {
      EXPECT_NE(hud->text.find("(flat out)"), std::string::npos) << hud->text;
    }
  }
}

// ---------------------------------------------------------------------------
// Mouse

TEST(DemoMouse, DragPullsTheClothParticleTowardTheCursorAndReleaseRemovesTheSpring) {
  const std::string dir = outputDirectory("Drag");
  // The seed preset's slow cloth: the mouse spring's pull, not gravity, dominates its motion.
  const std::string scene = "--scene cloth --preset seed --param links=4 --log-state state.txt ";
  ASSERT_EQ(runDemo(dir, scene + "--frames 1 --paused").exitCode, 0);
  const LoggedPane start = readStateLog(dir + "/state.txt").panes.at(0);
  // The bottom-right corner of the cloth, pulled down and to the right.
  const auto corner = std::max_element(start.particles.begin(), start.particles.end(),
                                       [](const LoggedParticle& a, const LoggedParticle& b) {
                                         return a.x.x() - a.x.y() < b.x.x() - b.x.y();
                                       }) - start.particles.begin();
  const Eigen::Vector2d from = start.particles[corner].x, to = from + Eigen::Vector2d(0.3, -0.3);
  std::ostringstream drag;
  drag << "5 down world " << from.x() << " " << from.y() << "\n";
  for (int k = 1; k <= 30; ++k) {
    const Eigen::Vector2d at = from + (to - from) * (k / 30.0);
    drag << 5 + k << " move world " << at.x() << " " << at.y() << "\n";
  }
  const std::string held = drag.str();
  const std::string released = held + "150 up world " + std::to_string(to.x()) + " " + std::to_string(to.y()) + "\n";

  ASSERT_EQ(runDemo(dir, scene + "--frames 150 --screenshot held.png", held).exitCode, 0);
  const LoggedPane dragging = readStateLog(dir + "/state.txt").panes.at(0);
  ASSERT_EQ(runDemo(dir, scene + "--frames 150").exitCode, 0);
  const LoggedPane alone = readStateLog(dir + "/state.txt").panes.at(0);
  ASSERT_EQ(runDemo(dir, scene + "--frames 160", released).exitCode, 0);
  const LoggedPane after = readStateLog(dir + "/state.txt").panes.at(0);

  const LoggedParticle target{to, {0, 0}, 0, false};
  EXPECT_EQ(dragging.mouseSprings, 1);
  EXPECT_LT(distance(dragging.particles[corner], target), 0.5 * (to - from).norm());
  EXPECT_LT(distance(dragging.particles[corner], target), distance(alone.particles[corner], target) - 0.1);
  EXPECT_EQ(after.mouseSprings, 0);
}

TEST(DemoMouse, PressInEmptySpaceGrabsNothing) {
  const std::string dir = outputDirectory("EmptyPress");
  const RunResult r = runDemo(dir, "--scene cloth --frames 20 --log-state state.txt",
                              "5 down world 0.9 -0.9\n6 move world 0.8 -0.8\n");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(readStateLog(dir + "/state.txt").panes[0].mouseSprings, 0);
}

TEST(DemoMouse, RightDragPinsAndMovesAParticleAndAClickUnpinsIt) {
  const std::string dir = outputDirectory("Pin");
  ASSERT_EQ(runDemo(dir, "--scene test-chain --frames 1 --paused --log-state state.txt").exitCode, 0);
  const LoggedPane start = readStateLog(dir + "/state.txt").panes.at(0);
  const int last = static_cast<int>(start.particles.size()) - 1;
  const Eigen::Vector2d from = start.particles[last].x, to = from + Eigen::Vector2d(-0.1, 0.2);
  std::ostringstream pin;
  pin << "3 down world " << from.x() << " " << from.y() << " right\n"
      << "4 move world " << to.x() << " " << to.y() << "\n"
      << "5 up world " << to.x() << " " << to.y() << " right\n";
  ASSERT_EQ(runDemo(dir, "--scene test-chain --frames 40 --log-state state.txt", pin.str()).exitCode, 0);
  const LoggedParticle pinned = readStateLog(dir + "/state.txt").panes[0].particles[last];
  EXPECT_TRUE(pinned.pinned);
  EXPECT_LT((pinned.x - to).norm(), 1e-2);
  std::ostringstream unpin;
  unpin << pin.str() << "10 down world " << to.x() << " " << to.y() << " shift-left\n"
        << "11 up world " << to.x() << " " << to.y() << " shift-left\n";
  ASSERT_EQ(runDemo(dir, "--scene test-chain --frames 40 --log-state state.txt", unpin.str()).exitCode, 0);
  EXPECT_FALSE(readStateLog(dir + "/state.txt").panes[0].particles[last].pinned);
}

// ---------------------------------------------------------------------------
// Screenshots agree with the simulation

TEST(DemoScreenshot, ParticlesWhereTheLogSaysBackgroundElsewhereHudNotEmpty) {
  const std::string dir = outputDirectory("Screenshot");
  // Constraints hidden (c) so that the rail line does not cross the background samples.
  const RunResult r = runDemo(dir, std::string(noPanel) + " --scene cloth --param links=8 --frames 90 "
                              "--screenshot shot.png --log-state state.txt", "0 key c\n");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Image image = readPng(dir + "/shot.png");
  const StateLog log = readStateLog(dir + "/state.txt");
  const LoggedPane& pane = log.panes.at(0);
  EXPECT_EQ(image.width, 900);
  EXPECT_EQ(image.height, 700);

  int checked = 0;
  const int drawn = particlesDrawn(image, log, pane, &checked);
  EXPECT_GE(checked, 50);
  EXPECT_EQ(drawn, checked);

  const std::vector<Eigen::Vector2i> empty = emptyPixels(log, pane);
  EXPECT_GE(empty.size(), 100u);
  for (const Eigen::Vector2i& px : empty) {
    const demo::Rgb c = image.at(px.x(), px.y());
    EXPECT_TRUE(near(c, demo::palette::background, 0)) << "at " << px.transpose() << ": " << int(c.r) << ","
                                                        << int(c.g) << "," << int(c.b);
  }
  // The HUD: text on its box in the bottom-left corner.
  const LoggedOverlay* hud = log.overlay("hud");
  ASSERT_NE(hud, nullptr);
  EXPECT_LT(hud->x, 20);
  EXPECT_GT(hud->y + hud->height, image.height - 20);
  EXPECT_GT(countNear(image, demo::palette::hudText, 40, hud->x, hud->y, hud->x + hud->width, hud->y + hud->height),
            300);
}

TEST(DemoScreenshot, ForceKeyAddsArrowPixelsNextToParticles) {
  const std::string dir = outputDirectory("ForceArrows");
  const std::string args = std::string(noPanel) + " --scene cloth --frames 60 --log-state state.txt ";
  ASSERT_EQ(runDemo(dir, args + "--screenshot plain.png", "0 key c\n").exitCode, 0);
  ASSERT_EQ(runDemo(dir, args + "--screenshot arrows.png", "0 key c\n0 key f\n").exitCode, 0);
  const Image plain = readPng(dir + "/plain.png"), arrows = readPng(dir + "/arrows.png");
  const StateLog log = readStateLog(dir + "/state.txt");
  const LoggedPane& pane = log.panes.at(0);

  // Pixels in each force type's arrow colour within 40 pixels of a particle.
  auto arrowPixels = [&](const Image& image, demo::Rgb colour) {
    int count = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        if (!near(image.at(x, y), colour, 20) || log.underOverlay({x, y})) continue;
        for (const LoggedParticle& q : pane.particles)
          if ((pane.toPixel(q.x) - Eigen::Vector2d(x, y)).norm() < 40) {
            ++count;
            break;
          }
      }
    return count;
  };
  const demo::Rgb gravity = demo::forceArrowColour("gravity"), spring = demo::forceArrowColour("spring");
  EXPECT_EQ(arrowPixels(plain, gravity), 0);
  EXPECT_EQ(arrowPixels(plain, spring), 0);
  EXPECT_GT(arrowPixels(arrows, gravity), 100);
  EXPECT_GT(arrowPixels(arrows, spring), 20);
}

// ---------------------------------------------------------------------------
// Compare mode

TEST(DemoCompare, EulerAndRk4PanesStartAlikeDivergeApartAndAreBothDrawn) {
  const std::string dir = outputDirectory("Compare");
  // The seed preset's slow chain, on which explicit Euler survives the 4 s run.
  const RunResult r = runDemo(dir, std::string(noPanel) + " --scene test-chain --preset seed --compare euler,rk4 --frames 240 "
                              "--screenshot shot.png --log-state state.txt");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const StateLog log = readStateLog(dir + "/state.txt");
  ASSERT_EQ(log.panes.size(), 2u);
  const LoggedPane &euler = log.panes[0], &rk4 = log.panes[1];
  EXPECT_EQ(euler.integrator, "euler");
  EXPECT_EQ(rk4.integrator, "rk4");
  EXPECT_EQ(euler.time, rk4.time);
  EXPECT_EQ(euler.steps, rk4.steps);
  ASSERT_EQ(euler.particles.size(), rk4.particles.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < euler.particles.size(); ++i)
    largest = std::max(largest, distance(euler.particles[i], rk4.particles[i]));
  EXPECT_GT(largest, 1e-4);
  // Side by side, not overlapping.
  EXPECT_LE(euler.pixelX + euler.pixelWidth, rk4.pixelX);

  const Image image = readPng(dir + "/shot.png");
  for (const LoggedPane* pane : {&euler, &rk4}) {
    int checked = 0;
    const int drawn = particlesDrawn(image, log, *pane, &checked);
    EXPECT_GE(checked, 5);
    EXPECT_EQ(drawn, checked);
    // Its HUD lines in its header strip, just above its world.
    const LoggedOverlay* header = nullptr;
    for (const LoggedOverlay& o : log.overlays)
      if (o.kind == "pane-hud" && o.x <= pane->pixelX && o.x + o.width >= pane->pixelX + pane->pixelWidth &&
          o.y + o.height <= pane->pixelY && o.y + o.height >= pane->pixelY - 20)
        header = &o;
    ASSERT_NE(header, nullptr);
    EXPECT_NE(header->text.find(pane->integrator), std::string::npos) << header->text;
    EXPECT_GT(countNear(image, demo::palette::hudText, 40, header->x, header->y, header->x + header->width,
                        header->y + header->height),
              100);
  }
}

TEST(DemoCompare, SameStartAsTheSinglePane) {
  // The rk4 pane of a compare run and a plain rk4 run see the same simulation.
  const std::string dir = outputDirectory("CompareSameStart");
  ASSERT_EQ(runDemo(dir, "--scene test-chain --compare euler,rk4 --frames 40 --log-state compare.txt").exitCode, 0);
  ASSERT_EQ(runDemo(dir, "--scene test-chain --integrator rk4 --frames 40 --log-state single.txt").exitCode, 0);
  const LoggedPane a = readStateLog(dir + "/compare.txt").panes.at(1), b = readStateLog(dir + "/single.txt").panes.at(0);
  for (std::size_t i = 0; i < a.particles.size(); ++i) EXPECT_EQ(a.particles[i].x, b.particles[i].x);
}

// ---------------------------------------------------------------------------
// Divergence

TEST(DemoDivergence, HugeDtDivergesShowsTheMessageRewindsAndKeepsRunning) {
  const std::string dir = outputDirectory("Divergence");
  // The seed preset's test chain with RK4 at dt = 0.5 blows up within a few seconds.
  const std::string args = std::string(noPanel) + " --scene test-chain --preset seed --integrator rk4 --dt 0.5 ";
  ASSERT_EQ(runDemo(dir, args + "--frames 300 --screenshot diverged.png --log-state diverged.txt").exitCode, 0);
  const StateLog diverged = readStateLog(dir + "/diverged.txt");
  ASSERT_TRUE(diverged.panes[0].diverged);
  EXPECT_TRUE(diverged.paused);
  const double divergedAt = diverged.panes[0].time;
  // The plots end at the state the HUD gives, the one that diverged.
  EXPECT_FLOAT_EQ(diverged.panes[0].plottedEnergy, diverged.panes[0].energy);
  EXPECT_FLOAT_EQ(diverged.panes[0].plottedConstraintError, diverged.panes[0].maxConstraintError);

  // The message, in its colour, in the top bar (never over the scene).
  const LoggedOverlay* bar = diverged.overlay("top-bar");
  ASSERT_NE(bar, nullptr);
  EXPECT_NE(bar->text.find("diverged at t = "), std::string::npos) << bar->text;
  auto messagePixels = [&](const Image& image) {
    return countNear(image, demo::palette::divergenceText, 30, bar->x, bar->y, bar->x + bar->width, bar->y + bar->height);
  };
  EXPECT_GT(messagePixels(readPng(dir + "/diverged.png")), 100);

  // b: back about one second, paused, message gone.
  ASSERT_EQ(runDemo(dir, args + "--frames 310 --screenshot rewound.png --log-state rewound.txt", "300 key b\n")
                .exitCode, 0);
  const StateLog rewound = readStateLog(dir + "/rewound.txt");
  EXPECT_FALSE(rewound.panes[0].diverged);
  EXPECT_TRUE(rewound.paused);
  EXPECT_LE(rewound.panes[0].time, divergedAt - 1.0 + 1e-9);
  EXPECT_GE(rewound.panes[0].time, divergedAt - 2.0);
  EXPECT_EQ(messagePixels(readPng(dir + "/rewound.png")), 0);

  // Smaller dt, run on: the program keeps going with finite values.
  ASSERT_EQ(runDemo(dir, args + "--frames 420 --log-state resumed.txt",
                    "300 key b\n301 key -\n302 key -\n303 key -\n304 key -\n305 key space\n").exitCode, 0);
  const StateLog resumed = readStateLog(dir + "/resumed.txt");
  EXPECT_FALSE(resumed.panes[0].diverged);
  EXPECT_FALSE(resumed.paused);
  EXPECT_GT(resumed.panes[0].time, rewound.panes[0].time + 1.5);
  EXPECT_TRUE(std::isfinite(resumed.panes[0].energy));
}

// ---------------------------------------------------------------------------
// Window shape

TEST(DemoView, ResizeKeepsTheWorldsAspectRatioAndShowsTheWholeView) {
  const std::string dir = outputDirectory("Resize");
  const RunResult r = runDemo(dir, "--scene pendulum --frames 40 --screenshot shot.png --log-state state.txt",
                              "5 resize 700 900\n");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Image image = readPng(dir + "/shot.png");
  EXPECT_EQ(image.width, 700);
  EXPECT_EQ(image.height, 900);
  const StateLog log = readStateLog(dir + "/state.txt");
  const LoggedPane& p = log.panes.at(0);
  const scenes::Scene scene = scenes::buildScene("pendulum");
  // One scale on both axes ...
  const double sx = p.pixelWidth / (p.worldMax.x() - p.worldMin.x());
  const double sy = p.pixelHeight / (p.worldMax.y() - p.worldMin.y());
  EXPECT_NEAR(sx, sy, 1e-9 * sx);
  // ... and the scene's whole view rectangle inside the pane, which fills the window beside the panel.
  EXPECT_LE(p.worldMin.x(), scene.viewMin.x() + 1e-12);
  EXPECT_LE(p.worldMin.y(), scene.viewMin.y() + 1e-12);
  EXPECT_GE(p.worldMax.x(), scene.viewMax.x() - 1e-12);
  EXPECT_GE(p.worldMax.y(), scene.viewMax.y() - 1e-12);
  // The world fills the window between the bars, beside the panel, inside its gutter.
  const LoggedOverlay *panel = log.overlay("panel"), *top = log.overlay("top-bar"), *bottom = log.overlay("hud");
  ASSERT_TRUE(panel && top && bottom);
  const int gutter = p.pixelX;
  EXPECT_GT(gutter, 0);
  EXPECT_EQ(top->height + 2 * gutter + p.pixelHeight + bottom->height, 900);
  EXPECT_EQ(p.pixelWidth + 2 * gutter + panel->width, 700);
}

TEST(DemoCompare, PanesCanDifferInDtAndKeepTheSameClock) {
  const std::string dir = outputDirectory("CompareDt");
  ASSERT_EQ(runDemo(dir, "--scene pendulum --compare rk4:0.02,rk4:0.005 --frames 60 --log-state state.txt").exitCode, 0);
  const StateLog log = readStateLog(dir + "/state.txt");
  ASSERT_EQ(log.panes.size(), 2u);
  EXPECT_DOUBLE_EQ(log.panes[0].dt, 0.02);
  EXPECT_DOUBLE_EQ(log.panes[1].dt, 0.005);
  EXPECT_NEAR(log.panes[0].time, 1.0, 1e-9);  // 60 frames of 1/60 s in both
  EXPECT_NEAR(log.panes[1].time, 1.0, 1e-9);
  EXPECT_EQ(log.panes[1].steps, 4 * log.panes[0].steps);
}

TEST(DemoCompare, MouseDragReachesEveryPane) {
  const std::string dir = outputDirectory("CompareDrag");
  // The seed preset's slow chain, whose tip the mouse spring holds against gravity.
  ASSERT_EQ(runDemo(dir, "--scene test-chain --preset seed --frames 1 --paused --log-state state.txt").exitCode, 0);
  const LoggedPane start = readStateLog(dir + "/state.txt").panes.at(0);
  const Eigen::Vector2d from = start.particles.back().x, to = from + Eigen::Vector2d(-0.2, 0.2);  // within reach
  std::ostringstream drag;
  drag << "2 down world " << from.x() << " " << from.y() << "\n3 move world " << to.x() << " " << to.y() << "\n";
  ASSERT_EQ(runDemo(dir, "--scene test-chain --preset seed --compare midpoint,rk4,symplectic-euler --frames 90 --log-state state.txt",
                    drag.str()).exitCode, 0);
  const StateLog log = readStateLog(dir + "/state.txt");
  ASSERT_EQ(log.panes.size(), 3u);
  for (const LoggedPane& pane : log.panes) {
    SCOPED_TRACE(pane.integrator);
    EXPECT_EQ(pane.mouseSprings, 1);
    EXPECT_LT((pane.particles.back().x - to).norm(), 0.5 * (from - to).norm());
  }
}

TEST(DemoDivergence, InCompareModeTheDivergedPaneStopsAloneAndRewindKeepsPanesTogether) {
  const std::string dir = outputDirectory("CompareDivergence");
  // The seed preset's test chain: RK4 diverges at dt = 0.5 and holds at 0.05.
  const std::string args = std::string(noPanel) + " --scene test-chain --preset seed --compare rk4:0.5,rk4:0.05 --log-state state.txt ";
  ASSERT_EQ(runDemo(dir, args + "--frames 300").exitCode, 0);
  const StateLog before = readStateLog(dir + "/state.txt");
  ASSERT_EQ(before.panes.size(), 2u);
  ASSERT_TRUE(before.panes[0].diverged);
  EXPECT_FALSE(before.panes[1].diverged);
  EXPECT_FALSE(before.paused);                        // the other pane ran on
  EXPECT_NEAR(before.panes[1].time, 5.0, 1e-9);       // 300 frames of 1/60 s
  EXPECT_LT(before.panes[0].time, before.panes[1].time);

  ASSERT_EQ(runDemo(dir, args + "--frames 302", "300 key b\n").exitCode, 0);
  const StateLog after = readStateLog(dir + "/state.txt");
  EXPECT_FALSE(after.panes[0].diverged);
  EXPECT_TRUE(after.paused);
  const double target = before.panes[0].time - 1.0;
  for (const LoggedPane& pane : after.panes) {
    EXPECT_LE(pane.time, target + 1e-9);
    EXPECT_GT(pane.time, target - 0.5 - 1e-9);  // the nearest snapshot, at most one dt (0.5) back
  }
}
