// particle-demo under hostile input: nothing a user or
// a script does ends the program except q, Esc or closing it, and no input
// reaches undefined behaviour (the sanitizer build runs these too).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>

#include "demo_driver.h"

using namespace demotest;

namespace {
bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string topBar(const StateLog& log) {
  const LoggedOverlay* top = log.overlay("top-bar");
  return top ? top->text : "";
}
}  // namespace

TEST(DemoHostile, DtHalvedToZeroOrDoubledToInfinityIsRefusedWithAMessage) {
  const std::string dir = outputDirectory("DtLimits");
  struct Case {
    const char* dt;
    const char* key;
    const char* message;
  };
  for (const Case& c : {Case{"5e-324", "-", "cannot be halved further"}, Case{"1e308", "+", "cannot be doubled further"}}) {
    SCOPED_TRACE(c.dt);
    const RunResult r = runDemo(dir, std::string("--scene oscillator --dt ") + c.dt + " --frames 6 --log-state state.txt",
                                std::string("1 key ") + c.key + "\n2 key " + c.key + "\n");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
    const StateLog log = readStateLog(dir + "/state.txt");
    EXPECT_EQ(log.frames, 6);
    EXPECT_DOUBLE_EQ(log.panes.at(0).dt, std::strtod(c.dt, nullptr));
    EXPECT_TRUE(contains(topBar(log), c.message)) << topBar(log);
  }
}

TEST(DemoHostile, GrabbingAHugeMassShowsAMessageAndGrabsNothing) {
  const std::string dir = outputDirectory("HugeMass");
  std::ofstream(dir + "/heavy.json") << R"({"name": "heavy", "integrator": "rk4", "dt": 0.01,
    "particles": [{"position": [0, 0], "mass": 7e306}],
    "forces": [{"type": "gravity", "acceleration": [0, -9.81]}]})";
  const RunResult r = runDemo(dir, "--scene-file heavy.json --frames 10 --log-state state.txt",
                              "2 down world 0 0\n3 move world 0.1 0.1\n");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const StateLog log = readStateLog(dir + "/state.txt");
  EXPECT_EQ(log.frames, 10);
  EXPECT_EQ(log.panes.at(0).mouseSprings, 0);
  EXPECT_TRUE(contains(topBar(log), "overflows for mass 7e+306")) << topBar(log);
}

TEST(DemoHostile, ResetAndCompareReReadingAnInvalidatedSceneFileShowTheMessage) {
  // The file is made invalid while the demo runs (at 60 frames/s, r comes
  // 9 s after the start, v later); both keep the panes as they were.
  const std::string dir = outputDirectory("EditedSceneFile");
  std::ifstream good(SCENES_DIR "/rod.json");
  std::stringstream text;
  text << good.rdbuf();
  std::ofstream(dir + "/scene.json") << text.str();
  std::thread editor([&] {
    std::this_thread::sleep_for(std::chrono::seconds(3));
    std::ofstream(dir + "/scene.json") << "{\"particles\": [}";
  });
  const RunResult r = runDemo(dir, "--scene-file scene.json --realtime --frames 600 --log-state state.txt",
                              "540 key r\n560 key v\n");
  editor.join();
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const StateLog log = readStateLog(dir + "/state.txt");
  EXPECT_EQ(log.frames, 600);
  EXPECT_EQ(log.panes.size(), 1u);
  EXPECT_GT(log.panes.at(0).time, 9.0);  // not reset: r failed and left the run going
  EXPECT_TRUE(contains(topBar(log), "scene.json")) << topBar(log);
}

TEST(DemoHostile, ANonFiniteStateIsDrawnAndTheWindowRunsOn) {
  // Explicit Euler at a huge dt: the chain's state overflows to inf and NaN,
  // which the renderer, camera and HUD must draw without a fault (UBSan checks
  // the float-to-int conversions in the sanitizer build).
  const std::string dir = outputDirectory("NonFinite");
  const RunResult r = runDemo(dir, "--scene test-chain --integrator euler --dt 5 --lockstep --frames 40 --log-state state.txt",
                              "20 key a\n21 wheel window 300 300 2\n22 key f\n");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const StateLog log = readStateLog(dir + "/state.txt");
  EXPECT_TRUE(log.panes.at(0).diverged);
  EXPECT_EQ(log.frames, 40);
}

TEST(DemoHostile, ScriptCoordinatesBeyondTwoToThe31AreClamped) {
  const std::string dir = outputDirectory("HugeCoordinates");
  const RunResult r = runDemo(dir, "--scene cloth --frames 10 --log-state state.txt",
                              "1 down window 3e9 -3e9\n2 move window 1e300 1e300\n3 up window 4294967296 0\n"
                              "4 down world 1e300 -1e300\n5 wheel window 1e12 1e12 1\n6 up world 1e300 1e300\n");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(readStateLog(dir + "/state.txt").frames, 10);
}

// --threads takes a decimal count in [1, 1024]: anything else is one line and exit 2.
TEST(DemoHostile, BadThreadCountsAreRefusedInOneLine) {
  const std::string dir = outputDirectory("BadThreads");
  for (const char* value : {"0", "-1", "1025", "2.5", "0x4", "nan", "''", "99999999999999999999"}) {
    SCOPED_TRACE(value);
    const RunResult r = runDemo(dir, std::string("--frames 2 --threads ") + value);
    EXPECT_EQ(r.exitCode, 2);
    ASSERT_EQ(r.errLines().size(), 1u) << r.err;
    EXPECT_TRUE(contains(r.err, "--threads")) << r.err;
  }
  EXPECT_EQ(runDemo(dir, "--scene pendulum --frames 2 --threads 1").exitCode, 0);
}

TEST(DemoHostile, ADirectoryAsTheScriptIsRejected) {
  const std::string dir = outputDirectory("ScriptDirectory");
  const RunResult r = runDemo(dir, "--script . --frames 2");
  EXPECT_EQ(r.exitCode, 2);
  ASSERT_EQ(r.errLines().size(), 1u) << r.err;
  EXPECT_TRUE(contains(r.err, "is not a regular file")) << r.err;
}

TEST(DemoHostile, AnOutputThatFailsAtTheEndExitsNonZero) {
  const std::string dir = outputDirectory("FullDisk");
  std::ifstream full("/dev/full");
  if (!full.good()) GTEST_SKIP() << "no /dev/full on this machine";
  const RunResult r = runDemo(dir, "--scene pendulum --frames 2 --log-state /dev/full");
  EXPECT_EQ(r.exitCode, 1);
  ASSERT_EQ(r.errLines().size(), 1u) << r.err;
  EXPECT_TRUE(contains(r.err, "/dev/full")) << r.err;
}

// The screenshot and the state log are written under NAME.partial and renamed
// when complete: a run whose writes succeed leaves both whole and no partial
// file; one that cannot write them (here NAME.partial is a directory) says so
// in one line per file, exits 1 and leaves the previous files as they were.
TEST(DemoHostile, OutputFilesAreReplacedWholeOrNotAtAll) {
  const std::string dir = outputDirectory("OutputsWhole");
  RunResult r = runDemo(dir, "--scene pendulum --frames 2 --screenshot shot.png --log-state state.txt");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(readStateLog(dir + "/state.txt").frames, 2);
  EXPECT_GT(readPng(dir + "/shot.png").width, 0);
  EXPECT_FALSE(std::ifstream(dir + "/state.txt.partial").good());
  EXPECT_FALSE(std::ifstream(dir + "/shot.png.partial").good());
  ASSERT_EQ(std::system(("mkdir '" + dir + "/state.txt.partial' '" + dir + "/shot.png.partial'").c_str()), 0);
  r = runDemo(dir, "--scene pendulum --frames 5 --screenshot shot.png --log-state state.txt");
  EXPECT_EQ(r.exitCode, 1) << r.err;
  ASSERT_EQ(r.errLines().size(), 2u) << r.err;
  EXPECT_TRUE(contains(r.err, "--screenshot")) << r.err;
  EXPECT_TRUE(contains(r.err, "--log-state")) << r.err;
  EXPECT_EQ(readStateLog(dir + "/state.txt").frames, 2) << "the previous state log is kept";
  EXPECT_GT(readPng(dir + "/shot.png").width, 0) << "the previous screenshot is kept";
}

// A seeded storm of random scripted events: keys (all but quitting), presses,
// drags and releases with every button, wheel clicks, resizes, coordinates far
// outside the window and the world. The demo must end on --frames with exit 0
// and a complete state log. The sanitizer build runs this under ASan+UBSan.
TEST(DemoHostile, TwoThousandRandomEventsNeverEndTheDemo) {
  const std::string dir = outputDirectory("RandomEvents");
  std::mt19937 rng(20261201);
  const std::string keys = "0123456789ibrafcgvlph.+-= ";
  auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
  auto coordinate = [&]() -> std::string {
    switch (pick(6)) {
      case 0: return std::to_string(pick(40000) - 20000) + "e5";
      case 1: return std::to_string(-pick(100));
      default: return std::to_string(pick(1200));
    }
  };
  const char* buttons[] = {"left", "right", "middle", "shift-left"};
  std::ostringstream script;
  const int events = 2000, frames = 400;
  for (int e = 0; e < events; ++e) {
    const int frame = e * frames / events;
    switch (pick(9)) {
      case 0: case 1: {
        const char k = keys[pick(static_cast<int>(keys.size()))];
        script << frame << " key " << (k == ' ' ? std::string("space") : std::string(1, k)) << "\n";
        break;
      }
      case 2: script << frame << " down window " << coordinate() << " " << coordinate() << " " << buttons[pick(4)] << "\n"; break;
      case 3: case 4: script << frame << " move window " << coordinate() << " " << coordinate() << "\n"; break;
      case 5: script << frame << " up window " << coordinate() << " " << coordinate() << " " << buttons[pick(4)] << "\n"; break;
      case 6: script << frame << " wheel window " << coordinate() << " " << coordinate() << " " << (pick(2) ? 1 : -1) << "\n"; break;
      case 7: script << frame << " down world " << (pick(200) - 100) / 100.0 << " " << (pick(200) - 100) / 100.0 << "\n"; break;
      default:
        if (pick(20) == 0) script << frame << " resize " << 300 + pick(900) << " " << 250 + pick(700) << "\n";
        else script << frame << " keydown space\n" << frame << " keyup space\n";
    }
  }
  const RunResult r = runDemo(dir, "--frames " + std::to_string(frames) + " --log-state state.txt", script.str());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(readStateLog(dir + "/state.txt").frames, frames);
}
