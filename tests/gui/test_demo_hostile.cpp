// particle-demo under hostile input: nothing a user or
// a script does ends the program except q, Esc or closing it, and no input
// reaches undefined behaviour (the sanitizer build runs these too).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>

#include "demo_driver.h"
#include "scene_file/json_parse.h"

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
  EXPECT_EQ(r.exitCode, 4);
  ASSERT_EQ(r.errLines().size(), 1u) << r.err;
  EXPECT_TRUE(contains(r.err, "/dev/full")) << r.err;
}

// The screenshot and the state log are written under NAME.partial and renamed
// when complete: a run whose writes succeed leaves both whole and no partial
// file; one that cannot write them (here NAME.partial is a directory) says so
// in one line per file, exits 4 and leaves the previous files as they were.
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
  EXPECT_EQ(r.exitCode, 4) << r.err;
  ASSERT_EQ(r.errLines().size(), 2u) << r.err;
  EXPECT_TRUE(contains(r.err, "--screenshot")) << r.err;
  EXPECT_TRUE(contains(r.err, "--log-state")) << r.err;
  EXPECT_EQ(readStateLog(dir + "/state.txt").frames, 2) << "the previous state log is kept";
  EXPECT_GT(readPng(dir + "/shot.png").width, 0) << "the previous screenshot is kept";
}

// Writes that fail while the demo runs (a frame of --record, the k key's
// screenshot; here their NAME.partial is a directory, as a full disk would
// refuse them) are one line each on stderr as they fail, and exit 4 at the
// end, as particle-lab's failed outputs; the demo runs on to its last frame.
TEST(DemoHostile, WritesThatFailWhileRunningAreOneLineOnStderrAndExit4) {
  const std::string dir = outputDirectory("FailedWrites");
  ASSERT_TRUE(std::filesystem::create_directories(dir + "/frames/frame-000003.png.partial"));
  RunResult r = runDemo(dir, "--scene pendulum --frames 6 --record frames --log-state state.txt");
  EXPECT_EQ(r.exitCode, 4) << r.err;
  ASSERT_EQ(r.errLines().size(), 1u) << r.err;
  EXPECT_TRUE(contains(r.err, "recording stopped: cannot write --record file")) << r.err;
  EXPECT_TRUE(contains(r.err, "frame-000003.png")) << r.err;
  EXPECT_EQ(readStateLog(dir + "/state.txt").frames, 6);
  EXPECT_GT(readPng(dir + "/frames/frame-000002.png").width, 0);
  EXPECT_FALSE(std::filesystem::exists(dir + "/frames/frame-000004.png")) << "recording stops at the failure";

  ASSERT_TRUE(std::filesystem::create_directories(dir + "/screenshot-000002.png.partial"));
  r = runDemo(dir, "--scene pendulum --frames 6 --log-state state.txt", "1 key k\n3 key k\n");
  EXPECT_EQ(r.exitCode, 4) << r.err;
  ASSERT_EQ(r.errLines().size(), 1u) << r.err;
  EXPECT_TRUE(contains(r.err, "cannot write the k key's screenshot file")) << r.err;
  EXPECT_GT(readPng(dir + "/screenshot-000004.png").width, 0) << "the next k still writes";
  EXPECT_EQ(readStateLog(dir + "/state.txt").frames, 6);
}

// The mouse tool (a pin held by the right button) names a particle of the
// panes it was pressed on. In build mode with space held, a right press used
// to pin a particle of the built scene; N (a new, empty scene) or z (undo)
// then replaced the panes and the next move placed a particle past the end
// (exit 139). The tool goes with the panes, and in build mode a right press
// is build mode's whatever is held.
TEST(DemoHostile, APinHeldAcrossASceneChangeGoesWithTheScene) {
  const std::string dir = outputDirectory("PinAcrossSceneChange");
  for (const char* change : {"N", "z", "e", "2", "v", "r"}) {
    SCOPED_TRACE(change);
    const std::string script = std::string("1 key e\n2 key n\n3 down world 0.9 -0.9\n4 up world 0.9 -0.9\n") +
                               "5 keydown space\n6 down world -0.225 0.6 right\n7 keyup space\n8 key " + change +
                               "\n9 move world 0.3 0.3\n10 move world 0.4 0.2\n11 up world 0.4 0.2 right\n" +
                               "12 down world -0.225 0.6 right\n13 key " + change + "\n14 move world 0.5 0.5\n";
    const RunResult r = runDemo(dir, "--scene cloth --frames 18 --log-state state.txt", script);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(readStateLog(dir + "/state.txt").frames, 18);
  }
}

// Build mode from the state now, with a pinned particle dragged into the
// wall: the reader refuses the state, and its message goes to the top bar
// while the panes run on (the refusal used to leave build mode half entered,
// and the panel then threw inside ImGui's frame: exit 134, "Forgot to call
// Render()").
TEST(DemoHostile, ARefusedBuildModeShowsTheReadersMessageAndTheDemoRunsOn) {
  const std::string dir = outputDirectory("RefusedBuildMode");
  ASSERT_EQ(runDemo(dir, "--scene cloth --paused --frames 2 --log-state layout.txt").exitCode, 0);
  const LoggedOverlay* now = readStateLog(dir + "/layout.txt").widget("build-now");
  ASSERT_NE(now, nullptr);
  const Eigen::Vector2d c = now->centre();
  const std::string at = "window " + std::to_string(c.x()) + " " + std::to_string(c.y());
  const std::string refuse = "2 down world -0.225 0.6 right\n3 move world -0.35 0.5\n4 move world -0.5 0.3\n"
                             "5 up world -0.5 0.3 right\n7 move " + at + "\n8 down " + at + " left\n9 up " + at +
                             " left\n";
  RunResult r = runDemo(dir, "--scene cloth --paused --frames 14 --log-state state.txt", refuse);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err, "");
  StateLog log = readStateLog(dir + "/state.txt");
  EXPECT_EQ(log.frames, 14);
  EXPECT_FALSE(log.build.active);
  EXPECT_TRUE(contains(topBar(log), "$.particles[0]: the particle starts inside colliders[")) << topBar(log);
  // Then e enters build mode from the scene as it starts, as ever.
  r = runDemo(dir, "--scene cloth --paused --frames 14 --log-state state.txt", refuse + "11 key e\n");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  log = readStateLog(dir + "/state.txt");
  EXPECT_TRUE(log.build.active);
  EXPECT_EQ(log.panes.at(0).particles.size(), 100u);
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

namespace {

// Random demo scripts (DemoHostile.RandomScriptsNeverEndTheDemo): each a run
// of its own from a scene drawn from the number keys' scenes and the example
// files, with events of every class a user or a script can send, aimed at
// the scene's particles (taken from its export) as often as at the window:
// keys of the running scene, of build mode and its tools, and scene keys;
// space held across frames; presses, drags and releases with every button;
// wheel clicks; build mode's select and edit with values of every JSON type;
// and runs of the gestures that break state (build mode, space held, a
// right press on a particle, a scene change or undo, a drag).
class DemoScriptFuzzer {
 public:
  explicit DemoScriptFuzzer(unsigned seed) : rng_(seed) {}

  // One script of `frames` frames over a scene whose particles start at `targets`.
  std::string script(int frames, const std::vector<Eigen::Vector2d>& targets) {
    targets_ = &targets;
    building_ = false;
    std::ostringstream out;
    out.precision(6);
    for (int frame = 1; frame < frames - 1; ++frame) {
      if (pick(3) != 0) continue;  // about one frame in three has events
      if (pick(3) == 0) {
        motif(out, frame);
        continue;
      }
      event(out, frame);
    }
    return out.str();
  }

 private:
  int pick(int n) { return static_cast<int>(rng_() % static_cast<unsigned>(n)); }
  template <std::size_t N>
  const char* pickOf(const char* const (&words)[N]) { return words[pick(static_cast<int>(N))]; }

  std::string where() {
    std::ostringstream at;
    if (!targets_->empty() && pick(3) != 0) {  // at a particle, within the pick radius or just beyond it
      const Eigen::Vector2d& p = (*targets_)[pick(static_cast<int>(targets_->size()))];
      const double jitter = pick(4) == 0 ? 0.1 : 0.005;
      at << "world " << p.x() + jitter * (pick(201) - 100) / 100.0 << " " << p.y() + jitter * (pick(201) - 100) / 100.0;
    } else if (pick(2) == 0) {
      at << "world " << (pick(301) - 150) / 100.0 << " " << (pick(301) - 150) / 100.0;
    } else {
      at << "window " << pick(360) - 20 << " " << pick(280) - 20;  // the runs' window is 320x240
    }
    return at.str();
  }

  void event(std::ostream& out, int frame) {
    static const char* const keys[] = {"e", "N", "z", "y", "s", "o", "enter", "tab", "m", "n", "k", "d", "j", "w",
                                       "t", "H", "B", "P", "C", "D", "x", "i", "+", "-", ".", "r", "b", "a", "A",
                                       "f", "c", "g", "v", "l", "p", "h", "space", "1", "2", "3", "4", "5", "6", "7",
                                       "8", "9"};
    static const char* const buttons[] = {"left", "right", "middle", "shift-left"};
    static const char* const fields[] = {"position", "mass", "radius", "pinned", "stiffness", "restLength", "length",
                                         "velocity", "restitution", "friction", "dt", "integrator", "name"};
    static const char* const values[] = {"1", "0", "-1", "0.5", "1e308", "-1e308", "5e-324", "0x10", "nan", "[0,0]",
                                         "[1e300,-1e300]", "[0.1,0.2]", "true", "\"text\"", "{}", "[]", "null", "rk4",
                                         "xpbd", "\"\\u202e\""};
    switch (pick(12)) {
      case 0: case 1: case 2: {
        const char* key = pickOf(keys);
        building_ ^= std::string(key) == "e";
        out << frame << " key " << key << "\n";
        break;
      }
      case 3: out << frame << " keydown space\n" << frame + 1 + pick(3) << " keyup space\n"; break;
      case 4: case 5: out << frame << " down " << where() << " " << pickOf(buttons) << "\n"; break;
      case 6: case 7: out << frame << " move " << where() << "\n"; break;
      case 8: out << frame << " up " << where() << " " << pickOf(buttons) << "\n"; break;
      case 9: out << frame << " wheel " << where() << " " << (pick(2) ? 1 : -1) * (1 + pick(3)) << "\n"; break;
      case 10: {
        static const char* const lists[] = {"particles", "forces", "constraints", "colliders", "walls", "collisionEdges"};
        if (pick(4) == 0) out << frame << " select scene\n";
        else out << frame << " select " << pickOf(lists) << " " << pick(12) << "\n";
        break;
      }
      default: {
        static const char* const targets[] = {"selected", "new", "build"};
        const char* target = pickOf(targets);
        const char* field = std::string(target) == "build" ? (pick(2) ? "grid" : "file") : pickOf(fields);
        out << frame << " edit " << target << " " << field << " "
            << (std::string(field) == "file" ? "fuzz.json" : pickOf(values)) << "\n";
      }
    }
  }

  // A run of gestures that changes the scene under a held tool, mostly in
  // build mode (the script's e keys toggle it, as far as the script knows).
  void motif(std::ostream& out, int& frame) {
    static const char* const changes[] = {"N", "z", "y", "e", "r", "v", "b", "1", "3", "6", "x", "i", "enter"};
    static const char* const buttons[] = {"right", "left", "shift-left", "right", "right"};
    if (!building_ && pick(4) != 0) {
      out << frame << " key e\n";
      building_ = true;
    }
    const bool space = pick(3) != 0;
    if (space) out << frame << " keydown space\n";
    out << ++frame << " down " << where() << " " << pickOf(buttons) << "\n";
    if (space && pick(2) == 0) out << frame << " keyup space\n";
    const char* change = pickOf(changes);
    building_ ^= std::string(change) == "e";
    out << ++frame << " key " << change << "\n";
    out << ++frame << " move " << where() << "\n";
    if (pick(2) == 0) out << frame << " move " << where() << "\n";
    if (pick(3) != 0) out << ++frame << " up " << where() << " " << pickOf(buttons) << "\n";
    if (space) out << frame << " keyup space\n";
  }

  std::mt19937 rng_;
  const std::vector<Eigen::Vector2d>* targets_ = nullptr;
  bool building_ = false;
};

// The particles' starting positions of a scene file's text.
std::vector<Eigen::Vector2d> particlePositions(const std::string& text) {
  std::vector<Eigen::Vector2d> positions;
  const scenes::Json document = scenes::parseJson(text);
  for (const scenes::Json& particle : document.at("particles"))
    positions.emplace_back(particle.at("position").at(0).get<double>(), particle.at("position").at(1).get<double>());
  return positions;
}

}  // namespace

// A few hundred random demo scripts (seeded), each run on its own: every one
// ends on --frames with exit 0, nothing on stderr and a complete state log
// (the generator found build mode's pin surviving a scene change, exit 139,
// and a refusal thrown inside ImGui's frame, exit 134).
TEST(DemoHostile, RandomScriptsNeverEndTheDemo) {
  const std::string dir = outputDirectory("RandomScripts");
  struct Start {
    std::string options;
    std::vector<Eigen::Vector2d> targets;
  };
  std::vector<Start> starts;
  for (const char* scene : {"cloth", "hair", "wire", "rod-chain", "test-chain", "taut-chain", "pendulum", "oscillator"}) {
    const RunResult exported = runParticleLab(dir, std::string("export --scene ") + scene);
    ASSERT_EQ(exported.exitCode, 0) << exported.err;
    starts.push_back({std::string("--scene ") + scene, particlePositions(exported.out)});
  }
  // The cloth swung anywhere in its range and of a few sizes: parameters that
  // start it inside its wall or nail are refused at the start (exit 2, one
  // line), the others run.
  for (const char* swing : {"-45", "-30", "-12", "60"}) {
    const std::string params = std::string(" --param swing=") + swing + " --param width=8 --param height=8";
    const RunResult exported = runParticleLab(dir, "export --scene cloth" + params);
    starts.push_back({"--scene cloth" + params, exported.exitCode == 0 ? particlePositions(exported.out)
                                                                         : std::vector<Eigen::Vector2d>{}});
  }
  for (const char* file : {"disc.json", "polygon.json", "capsule.json", "rod.json", "walls.json", "wind.json"}) {
    std::ifstream in(std::string(SCENES_DIR) + "/" + file);
    std::stringstream text;
    text << in.rdbuf();
    starts.push_back({std::string("--scene-file ") + SCENES_DIR + "/" + file, particlePositions(text.str())});
  }
  DemoScriptFuzzer fuzzer(20261219);
  std::mt19937 choose(20261220);
  const int scripts = 240;
  int refused = 0;
  for (int k = 0; k < scripts; ++k) {
    const Start& start = starts[choose() % starts.size()];
    const int frames = 16 + static_cast<int>(choose() % 16);
    const std::string script = fuzzer.script(frames, start.targets);
    // A small window: a frame of the panel and the scene costs about 7 ms there
    // (some 20 ms at 640x480), and a run about 0.3 s to start.
    const std::string options = start.options + " --window 320x240 --frames " + std::to_string(frames) +
                                " --log-state state.txt" + (choose() % 4 == 0 ? " --paused" : "");
    std::filesystem::remove(dir + "/state.txt");
    const RunResult r = runDemo(dir, options, script);
    const bool whole = std::ifstream(dir + "/state.txt").good() && readStateLog(dir + "/state.txt").frames == frames;
    const bool refusedAtStart = r.exitCode == 2 && r.errLines().size() == 1 && start.targets.empty() &&
                                r.err.rfind("particle-demo: scene 'cloth': particle ", 0) == 0;
    if (refusedAtStart) {
      ++refused;
      continue;
    }
    if (r.exitCode != 0 || !r.err.empty() || !whole) {
      ADD_FAILURE() << "script " << k << ": exit " << r.exitCode << ", stderr '" << r.err << "', state log "
                    << (whole ? "whole" : "missing or short") << "\nparticle-demo " << options
                    << " --script script.txt, with script.txt:\n" << script;
      return;
    }
  }
  std::printf("[ fuzz     ] %d demo scripts: %d ran to their last frame, %d refused at the start\n", scripts,
              scripts - refused, refused);
  EXPECT_GT(refused, 0);
  EXPECT_LT(refused, scripts / 2);
}
