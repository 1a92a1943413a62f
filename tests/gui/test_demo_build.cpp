// Build mode under Xvfb, driven by scripted input as a user would drive it:
// scenes built with the tools, saved with s, checked in the file, and run by
// the demo and by particle-lab from that file, bit for bit; undo and redo;
// bad files and refused edits as messages, never a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "demo_driver.h"
#include "scene_file/json_parse.h"
#include "scene_file/scene_file.h"

using namespace demotest;

namespace {

// A script of timed input, one event per frame, in world coordinates.
class Script {
 public:
  Script& key(const std::string& k) { return line("key " + k); }
  Script& click(double x, double y) { return point("down", x, y).point("up", x, y); }
  Script& drag(double x0, double y0, double x1, double y1) {
    return point("down", x0, y0).point("move", x1, y1).point("up", x1, y1);
  }
  Script& edit(const std::string& target, const std::string& field, const std::string& value) {
    return line("edit " + target + " " + field + " " + value);
  }
  Script& select(const std::string& what) { return line("select " + what); }
  // A click on a panel control, at its centre in window pixels.
  Script& clickWindow(const LoggedOverlay& widget) {
    const Eigen::Vector2d c = widget.centre();
    const std::string at = "window " + std::to_string(c.x()) + " " + std::to_string(c.y());
    return line("move " + at).line("down " + at + " left").line("up " + at + " left");
  }
  Script& save(const std::string& file) { return edit("build", "file", file).key("s"); }
  Script& wait(long long frames) {
    frame_ += frames;
    return *this;
  }
  const std::string& text() const { return text_; }
  long long frames() const { return frame_; }

 private:
  Script& line(const std::string& event) {
    text_ += std::to_string(frame_++) + " " + event + "\n";
    return *this;
  }
  Script& point(const char* action, double x, double y) {
    std::ostringstream s;
    s.precision(17);
    s << action << " world " << x << " " << y;
    return line(s.str());
  }
  long long frame_ = 0;
  std::string text_;
};

// Enters build mode on a new, empty scene with a 0.1 grid.
Script emptyScene() {
  Script s;
  s.key("e").key("N").edit("build", "grid", "0.1");
  return s;
}

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
scenes::Json readJson(const std::string& path) { return scenes::parseJson(readText(path)); }

// The demo's run: exit code 0, its state log.
StateLog runScript(const std::string& dir, const Script& script, const std::string& options = "") {
  const RunResult r = runDemo(dir, "--lockstep --frames " + std::to_string(script.frames() + 1) +
                                       " --log-state state.txt " + options,
                              script.text());
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err, "");
  return readStateLog(dir + "/state.txt");
}

// particle-lab run --scene-file for as many steps as the pane took: every
// particle's position and velocity equal to the pane's, bit for bit (the log
// writes 17 significant digits, the trajectory the shortest round trip).
void expectParticleLabAgrees(const std::string& dir, const std::string& file, const LoggedPane& pane) {
  ASSERT_GT(pane.steps, 10);
  const std::string steps = std::to_string(pane.steps);
  const RunResult lab =
      runParticleLab(dir, "run --scene-file " + file + " --steps " + steps + " --trajectory lab.csv --every " + steps);
  ASSERT_EQ(lab.exitCode, 0) << lab.err;
  std::ifstream in(dir + "/lab.csv");
  std::map<int, std::vector<double>> last;  // particle → x, y, vx, vy at the last step
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<double> f;
    std::stringstream s(line);
    for (std::string field; std::getline(s, field, ',');) f.push_back(std::strtod(field.c_str(), nullptr));
    if (static_cast<long long>(f.at(0)) == pane.steps) last[static_cast<int>(f.at(2))] = {f[3], f[4], f[5], f[6]};
  }
  ASSERT_EQ(last.size(), pane.particles.size());
  for (std::size_t i = 0; i < pane.particles.size(); ++i) {
    SCOPED_TRACE("particle " + std::to_string(i) + " after " + steps + " steps");
    const LoggedParticle& p = pane.particles[i];
    EXPECT_EQ(p.x.x(), last[static_cast<int>(i)][0]);
    EXPECT_EQ(p.x.y(), last[static_cast<int>(i)][1]);
    EXPECT_EQ(p.v.x(), last[static_cast<int>(i)][2]);
    EXPECT_EQ(p.v.y(), last[static_cast<int>(i)][3]);
  }
}

// The saved file is what particle-lab's export writes of it (one writer, the
// shortest round-trip numbers); the scene built and run in the demo, and the
// file loaded by the demo, run as particle-lab runs the file.
void expectSavedSceneRunsAsParticleLab(const std::string& dir, const std::string& file, const StateLog& built) {
  const RunResult exported = runParticleLab(dir, "export --scene-file " + file);
  ASSERT_EQ(exported.exitCode, 0) << exported.err;
  EXPECT_EQ(exported.out, readText(dir + "/" + file));
  EXPECT_FALSE(built.build.active);
  expectParticleLabAgrees(dir, file, built.panes.at(0));
  const RunResult reload =
      runDemo(dir, "--scene-file " + file + " --lockstep --frames 150 --no-panel --log-state reload.txt");
  ASSERT_EQ(reload.exitCode, 0) << reload.err;
  expectParticleLabAgrees(dir, file, readStateLog(dir + "/reload.txt").panes.at(0));
}

Eigen::Vector2d positionOf(const scenes::Json& particle) {
  return {particle["position"][0].get<double>(), particle["position"][1].get<double>()};
}

}  // namespace

// A pinned particle and five rods drawn from it, each from the last end:
// six particles 0.1 apart on the grid, the rods 0.1 long.
TEST(DemoBuild, AChainBuiltWithTheMouseSavesAndRunsAsParticleLab) {
  const std::string dir = outputDirectory("BuildChain");
  Script s = emptyScene();
  s.key("n").edit("new", "pinned", "true").click(-0.2, 0.5).edit("new", "pinned", "false").key("d");
  for (int k = 0; k < 5; ++k) s.drag(-0.2 + 0.1 * k, 0.5, -0.1 + 0.1 * k, 0.5);
  s.save("chain.json").key("e").wait(120);
  const StateLog log = runScript(dir, s);

  const scenes::Json file = readJson(dir + "/chain.json");
  ASSERT_EQ(file["particles"].size(), 6u);
  ASSERT_EQ(file["constraints"].size(), 5u);
  for (int k = 0; k < 6; ++k) {
    EXPECT_EQ(positionOf(file["particles"][k]), Eigen::Vector2d(std::strtod(std::to_string(-0.2 + 0.1 * k).c_str(), nullptr), 0.5))
        << "a grid point is saved as the decimal it reads";
    EXPECT_EQ(file["particles"][k]["mass"], 0.1);
    EXPECT_EQ(file["particles"][k].value("pinned", false), k == 0) << k;
  }
  for (int k = 0; k < 5; ++k) {
    EXPECT_EQ(file["constraints"][k]["type"], "rod");
    EXPECT_EQ(file["constraints"][k]["particles"], scenes::Json({k, k + 1}));
    EXPECT_NEAR(file["constraints"][k]["length"].get<double>(), 0.1, 1e-12);
  }
  EXPECT_EQ(file["forces"], scenes::Json::parse(R"([{"type":"gravity","acceleration":[0.0,-9.81]}])"));
  expectSavedSceneRunsAsParticleLab(dir, "chain.json", log);
}

// A 3×3 patch of collidable particles, its top row pinned, twelve springs
// between neighbours, falling onto a disc drawn under it.
TEST(DemoBuild, AClothPatchWithAColliderSavesAndRunsAsParticleLab) {
  const std::string dir = outputDirectory("BuildCloth");
  Script s = emptyScene();
  s.key("n").edit("new", "radius", "0.01");
  for (int row = 0; row < 3; ++row) {
    s.edit("new", "pinned", row == 0 ? "true" : "false");
    for (int col = 0; col < 3; ++col) s.click(0.1 * col, 0.4 - 0.1 * row);
  }
  s.key("k").edit("new", "stiffness", "30").edit("new", "damping", "0.5");
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 2; ++col) s.drag(0.1 * col, 0.4 - 0.1 * row, 0.1 * col + 0.1, 0.4 - 0.1 * row);
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 2; ++row) s.drag(0.1 * col, 0.4 - 0.1 * row, 0.1 * col, 0.3 - 0.1 * row);
  s.key("D").edit("new", "friction", "0.3").edit("build", "grid", "0.05").drag(0.1, 0.0, 0.1, 0.15);
  s.save("cloth.json").key("e").wait(400);
  const StateLog log = runScript(dir, s);

  const scenes::Json file = readJson(dir + "/cloth.json");
  ASSERT_EQ(file["particles"].size(), 9u);
  for (int i = 0; i < 9; ++i) {
    EXPECT_EQ(file["particles"][i].value("pinned", false), i < 3) << i;
    EXPECT_EQ(file["particles"][i]["radius"], 0.01) << i;
  }
  ASSERT_EQ(file["forces"].size(), 13u);  // gravity and 12 springs
  for (std::size_t k = 1; k < 13; ++k) {
    EXPECT_EQ(file["forces"][k]["type"], "spring");
    EXPECT_NEAR(file["forces"][k]["restLength"].get<double>(), 0.1, 1e-12);
    EXPECT_EQ(file["forces"][k]["stiffness"], 30.0);
    EXPECT_EQ(file["forces"][k]["damping"], 0.5);
  }
  ASSERT_EQ(file["colliders"].size(), 1u);
  EXPECT_EQ(file["colliders"][0]["type"], "disc");
  EXPECT_EQ(file["colliders"][0]["centre"], scenes::Json({0.1, 0.0}));
  EXPECT_NEAR(file["colliders"][0]["radius"].get<double>(), 0.15, 1e-12);
  EXPECT_EQ(file["colliders"][0]["friction"], 0.3);
  // The patch sags onto the disc (its springs alone would let its bottom row
  // hang 0.1 lower): its bottom middle particle rests on top, 0.15 + 0.01
  // from the centre.
  const LoggedParticle& bottom = log.panes.at(0).particles.at(7);
  EXPECT_NEAR((bottom.x - Eigen::Vector2d(0.1, 0.0)).norm(), 0.16, 0.002);
  expectSavedSceneRunsAsParticleLab(dir, "cloth.json", log);
}

// A bead on a circular wire with a weight on a spring below it, and a
// particle on a vertical line that falls onto a half-plane floor.
TEST(DemoBuild, AWireALineAndAFloorSaveAndRunAsParticleLab) {
  const std::string dir = outputDirectory("BuildWire");
  Script s = emptyScene();
  s.key("w").drag(0.0, 0.5, 0.3, 0.5);
  s.key("k").drag(0.3, 0.5, 0.3, 0.3);
  s.key("t").drag(-0.5, 0.3, -0.5, 0.5);
  s.key("H").edit("new", "restitution", "0").drag(0.0, 0.0, 0.0, 0.1);
  s.save("wire.json").key("e").wait(200);
  const StateLog log = runScript(dir, s);

  const scenes::Json file = readJson(dir + "/wire.json");
  ASSERT_EQ(file["particles"].size(), 3u);
  ASSERT_EQ(file["constraints"].size(), 2u);
  EXPECT_EQ(file["constraints"][0]["type"], "circular-wire");
  EXPECT_EQ(file["constraints"][0]["particle"], 0);
  EXPECT_EQ(file["constraints"][0]["centre"], scenes::Json({0.0, 0.5}));
  EXPECT_NEAR(file["constraints"][0]["radius"].get<double>(), 0.3, 1e-12);
  EXPECT_EQ(file["constraints"][1]["type"], "line");
  EXPECT_EQ(file["constraints"][1]["particle"], 2);
  EXPECT_NEAR(file["constraints"][1]["angle"].get<double>(), std::acos(0.0), 1e-12);
  EXPECT_EQ(file["forces"][1]["particles"], scenes::Json({0, 1}));
  EXPECT_EQ(file["colliders"][0]["type"], "halfPlane");
  // The line's particle fell onto the floor and stays; the bead stays on its wire.
  EXPECT_NEAR(log.panes.at(0).particles.at(2).x.y(), 0.0, 1e-6);
  EXPECT_NEAR(log.panes.at(0).particles.at(2).x.x(), -0.5, 1e-9);
  EXPECT_NEAR((log.panes.at(0).particles.at(0).x - Eigen::Vector2d(0.0, 0.5)).norm(), 0.3, 1e-3);
  expectSavedSceneRunsAsParticleLab(dir, "wire.json", log);
}

// Every tool once: an angle spring, a box, a polygon (clicked clockwise) and
// a capsule besides the rest.
TEST(DemoBuild, EveryKindOfObjectSavesAndRunsAsParticleLab) {
  const std::string dir = outputDirectory("BuildEveryKind");
  Script s = emptyScene();
  s.key("n").edit("new", "pinned", "true").click(-0.5, 0.5).edit("new", "pinned", "false");
  s.key("d").drag(-0.5, 0.5, -0.3, 0.5).key("k").drag(-0.3, 0.5, -0.1, 0.5);
  s.key("j").click(-0.5, 0.5).click(-0.3, 0.5).click(-0.1, 0.5);
  s.key("B").drag(-0.9, -0.9, -0.6, -0.7);
  s.key("P").click(0.3, -0.5).click(0.3, -0.3).click(0.6, -0.3).click(0.6, -0.5).key("enter");
  s.key("C").drag(-0.4, -0.2, 0.0, -0.3);
  s.save("every.json").key("e").wait(120);
  const StateLog log = runScript(dir, s);

  const scenes::Json file = readJson(dir + "/every.json");
  std::vector<std::string> types;
  for (const char* list : {"forces", "constraints", "colliders"})
    for (const scenes::Json& object : file[list]) types.push_back(object["type"]);
  EXPECT_EQ(types, (std::vector<std::string>{"gravity", "spring", "angular-spring", "rod", "box", "polygon", "capsule"}));
  EXPECT_DOUBLE_EQ(std::abs(file["forces"][2]["restAngle"].get<double>()), std::acos(-1.0));  // a straight angle
  EXPECT_EQ(file["colliders"][1]["vertices"], scenes::Json::parse("[[0.3,-0.5],[0.6,-0.5],[0.6,-0.3],[0.3,-0.3]]"));
  expectSavedSceneRunsAsParticleLab(dir, "every.json", log);
}

// Each kind of edit undone gives back the file saved before it, byte for
// byte, and redone the file saved after it.
TEST(DemoBuild, UndoGivesTheStateBeforeAnEditAndRedoTheStateAfter) {
  const std::string dir = outputDirectory("BuildUndo");
  Script s = emptyScene();
  s.key("n").click(0.0, 0.0).click(0.2, 0.0).click(0.4, 0.0);
  const std::vector<std::pair<std::string, std::function<void(Script&)>>> edits = {
      {"add", [](Script& t) { t.key("k").drag(0.0, 0.0, 0.2, 0.0); }},
      {"move", [](Script& t) { t.key("m").drag(0.2, 0.0, 0.2, 0.3); }},
      {"field", [](Script& t) { t.select("forces 1").edit("selected", "stiffness", "123.5"); }},
      {"scene-field", [](Script& t) { t.select("scene").edit("selected", "dt", "0.001"); }},
      {"delete", [](Script& t) { t.key("x").click(0.0, 0.0); }},
      {"collider", [](Script& t) { t.key("B").drag(-0.5, -0.9, 0.5, -0.6); }},
      {"new", [](Script& t) { t.key("N"); }},
  };
  for (const auto& [name, edit] : edits) {
    s.save(name + "-before.json");
    edit(s);
    s.save(name + "-after.json").key("z").save(name + "-undone.json").key("y").save(name + "-redone.json");
  }
  const StateLog log = runScript(dir, s);
  EXPECT_TRUE(log.build.active);
  for (const auto& [name, edit] : edits) {
    SCOPED_TRACE(name);
    const std::string before = readText(dir + "/" + name + "-before.json"), after = readText(dir + "/" + name + "-after.json");
    ASSERT_FALSE(before.empty());
    EXPECT_NE(before, after);
    EXPECT_EQ(readText(dir + "/" + name + "-undone.json"), before);
    EXPECT_EQ(readText(dir + "/" + name + "-redone.json"), after);
  }
  // The edits happened as drawn: the move, the field, the delete.
  EXPECT_EQ(positionOf(readJson(dir + "/move-after.json")["particles"][1]), Eigen::Vector2d(0.2, 0.3));
  EXPECT_EQ(readJson(dir + "/field-after.json")["forces"][1]["stiffness"], 123.5);
  EXPECT_EQ(readJson(dir + "/scene-field-after.json")["dt"], 0.001);
  EXPECT_EQ(readJson(dir + "/delete-after.json")["particles"].size(), 2u);
  EXPECT_EQ(readJson(dir + "/delete-after.json")["forces"].size(), 1u);  // the spring on it went too
  EXPECT_EQ(readJson(dir + "/new-after.json")["particles"].size(), 0u);
}

// Build mode starts from the scene on screen (as particle-lab exports it) or
// from a file it opens, and saves either unchanged as particle-lab exports it.
TEST(DemoBuild, StartsFromAnySceneOrAnOpenedFile) {
  const std::string dir = outputDirectory("BuildStart");
  Script s;
  s.key("e").save("pendulum.json").edit("build", "file", std::string(SCENES_DIR) + "/disc.json").key("o");
  s.save("disc.json");
  runScript(dir, s, "--scene pendulum");
  const RunResult pendulum = runParticleLab(dir, "export --scene pendulum");
  ASSERT_EQ(pendulum.exitCode, 0);
  EXPECT_EQ(readText(dir + "/pendulum.json"), pendulum.out);
  const RunResult disc = runParticleLab(dir, "export --scene-file " SCENES_DIR "/disc.json");
  ASSERT_EQ(disc.exitCode, 0);
  EXPECT_EQ(readText(dir + "/disc.json"), disc.out);
}

// The panel's Build section: its buttons do what the keys do.
TEST(DemoBuild, ThePanelsButtonsEnterBuildModeStartAfreshAndSave) {
  const std::string dir = outputDirectory("BuildPanel");
  ASSERT_EQ(runDemo(dir, "--scene pendulum --frames 2 --log-state layout.txt").exitCode, 0);
  const LoggedOverlay* enter = readStateLog(dir + "/layout.txt").widget("build");
  ASSERT_NE(enter, nullptr);
  Script clickBuild;
  clickBuild.clickWindow(*enter);
  EXPECT_TRUE(runScript(dir, clickBuild, "--scene pendulum").build.active);

  Script layoutInBuildMode;
  layoutInBuildMode.key("e");
  const StateLog inBuildMode = runScript(dir, layoutInBuildMode, "--scene pendulum");
  const LoggedOverlay *fresh = inBuildMode.widget("build-new"), *save = inBuildMode.widget("build-save");
  ASSERT_NE(fresh, nullptr);
  ASSERT_NE(save, nullptr);
  Script s;
  s.key("e").clickWindow(*fresh).edit("build", "file", "panel.json").clickWindow(*save);
  const StateLog log = runScript(dir, s, "--scene pendulum");
  EXPECT_TRUE(log.build.active);
  EXPECT_EQ(log.build.file, "panel.json");
  EXPECT_EQ(log.panes.at(0).particles.size(), 0u);
  EXPECT_EQ(readJson(dir + "/panel.json")["particles"].size(), 0u);
  EXPECT_NE(log.text().find("saved panel.json"), std::string::npos) << log.text();
}

// "from the state now" edits the scene as it is at that moment: the
// pendulum's bead where it has swung to, with its velocity, at t = 0.
TEST(DemoBuild, BuildingFromTheStateNowKeepsThePositionsAndVelocities) {
  const std::string dir = outputDirectory("BuildNow");
  ASSERT_EQ(runDemo(dir, "--scene pendulum --frames 2 --log-state layout.txt").exitCode, 0);
  const LoggedOverlay* now = readStateLog(dir + "/layout.txt").widget("build-now");
  ASSERT_NE(now, nullptr);
  Script s;
  s.wait(40).clickWindow(*now).save("now.json");
  const StateLog log = runScript(dir, s, "--scene pendulum");
  EXPECT_TRUE(log.build.active);
  const scenes::Json bead = readJson(dir + "/now.json")["particles"][0];
  const scenes::Json start = scenes::parseJson(runParticleLab(dir, "export --scene pendulum").out)["particles"][0];
  EXPECT_GT((positionOf(bead) - positionOf(start)).norm(), 0.01);  // it swung on for 40 frames
  EXPECT_GT(std::hypot(bead["velocity"][0].get<double>(), bead["velocity"][1].get<double>()), 0.1);
  // The clock goes with the state (a scene file's "time"): the copy is the run as it was, not a fresh start.
  EXPECT_GT(log.panes.at(0).time, 0.0);
  EXPECT_EQ(log.panes.at(0).time, readJson(dir + "/now.json")["time"].get<double>());
  EXPECT_EQ(log.panes.at(0).particles.at(0).x, positionOf(bead));
}

// What cannot be done is said in the top bar, in one line, and changes
// nothing: the demo runs on and exits 0.
TEST(DemoBuild, BadFilesAndRefusedEditsGiveAMessageAndChangeNothing) {
  const std::string dir = outputDirectory("BuildBadInput");
  std::ofstream(dir + "/not-a-scene.txt") << "hello\n";
  std::ofstream(dir + "/no-particles.json") << "{\"forces\": []}\n";
  std::filesystem::create_directories(dir + "/a-directory");
  struct Case {
    std::string name, events, message;
  };
  const std::vector<Case> cases = {
      {"unwritable", "save:" + dir + "/no/such/dir/x.json", "cannot write scene file '" + dir + "/no/such/dir/x.json'"},
      {"directory", "save:" + dir + "/a-directory", "cannot write scene file '" + dir + "/a-directory'"},
      {"not JSON", "open:not-a-scene.txt", "not-a-scene.txt: $: expected valid JSON"},
      {"no particles", "open:no-particles.json", "no-particles.json: $.particles: expected an array of particles"},
      {"missing", "open:missing.json", "missing.json: cannot read the file"},
      {"open a directory", "open:a-directory", "a-directory: cannot read the file (a directory"},
      {"inside a collider", "disc", "$.particles[0]: the particle starts inside colliders[0]"},
      {"bad field", "mass", "$.particles[0].mass: expected a number > 0, got -1"},
      {"no such object", "select", "select: the scene has no particles[7]"},
      {"bad tool field", "tool-field", "the particle tool has no number field 'stiffness'"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    Script s = emptyScene();
    s.key("n").click(0.0, 0.0);
    const std::string argument = c.events.substr(c.events.find(':') + 1);
    if (c.events.rfind("save:", 0) == 0) s.save(argument);
    if (c.events.rfind("open:", 0) == 0) s.edit("build", "file", argument).key("o");
    if (c.events == "disc") s.key("D").drag(0.0, 0.1, 0.0, -0.2);
    if (c.events == "mass") s.select("particles 0").edit("selected", "mass", "-1");
    if (c.events == "select") s.select("particles 7");
    if (c.events == "tool-field") s.edit("new", "stiffness", "5");
    const StateLog log = runScript(dir, s);
    const LoggedOverlay* top = log.overlay("top-bar");
    ASSERT_NE(top, nullptr);
    EXPECT_NE(top->joined().find(c.message), std::string::npos) << top->text;
    EXPECT_TRUE(log.build.active);
    EXPECT_EQ(log.build.historyStates, 3);  // the start, the new scene, the particle: nothing more
    ASSERT_EQ(log.panes.at(0).particles.size(), 1u);
    EXPECT_EQ(log.panes.at(0).particles[0].x, Eigen::Vector2d(0.0, 0.0));
    EXPECT_FALSE(std::filesystem::exists(dir + "/no/such/dir/x.json"));
  }
}

// Select and edit need build mode; outside it they say so.
TEST(DemoBuild, ScriptedEditsOutsideBuildModeSaySo) {
  const std::string dir = outputDirectory("BuildOutside");
  Script s;
  s.edit("selected", "dt", "0.5");
  const StateLog log = runScript(dir, s, "--scene pendulum");
  EXPECT_NE(log.overlay("top-bar")->text.find("select and edit act in build mode (e enters it)"), std::string::npos);
  EXPECT_DOUBLE_EQ(log.panes.at(0).dt, 0.005);
}

// The example of demos/gui/SCRIPTING.md builds what it says and saves it.
TEST(DemoBuild, TheScriptingGuidesExampleBuildsAndSavesAChain) {
  const std::string all = readText(SCRIPTING_MD);
  const auto start = all.find("# build a chain of two rods");
  ASSERT_NE(start, std::string::npos);
  const std::string example = all.substr(start, all.find("```", start) - start);
  const std::string dir = outputDirectory("BuildScriptingExample");
  const RunResult r = runDemo(dir, "--lockstep --frames 200 --log-state state.txt", example);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const scenes::Json file = readJson(dir + "/chain.json");
  EXPECT_EQ(file["particles"].size(), 3u);
  EXPECT_EQ(file["constraints"].size(), 2u);
  EXPECT_TRUE(file["particles"][0]["pinned"].get<bool>());
  EXPECT_FALSE(file["particles"][1].contains("pinned"));
  EXPECT_FALSE(file["particles"][2].contains("pinned"));
  const StateLog log = readStateLog(dir + "/state.txt");
  EXPECT_LT(log.panes.at(0).particles.at(2).x.y(), 0.45);  // it swings down
  expectParticleLabAgrees(dir, "chain.json", log.panes.at(0));
}
