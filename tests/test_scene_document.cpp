// Build mode's model without a window: the scene-file document and its edits
// (demos/gui/scene_document.h), the tools (build_tools.h), their gestures
// (build_mode.h) and the edit history (edit_history.h).
#include <gtest/gtest.h>

#include <cmath>

#include "build_geometry.h"
#include "build_mode.h"
#include "build_tools.h"
#include "edit_history.h"
#include "integrators/rk4.h"
#include "particles/constants.h"
#include "scene_document.h"
#include "scene_file/scene_file.h"

using namespace demo;

namespace demo {
void PrintTo(const ObjectRef& ref, std::ostream* out) { *out << ref.name(); }
}  // namespace demo

namespace {

Json particleAt(double x, double y) { return {{"position", {x, y}}, {"mass", 0.1}}; }

// Four particles on a row 0.1 apart, the first pinned, with every kind of
// object that names particles.
Json fourParticles() {
  Json d = emptyDocument();
  for (int i = 0; i < 4; ++i) d["particles"].push_back(particleAt(0.1 * i, 0.0));
  d["particles"][0]["pinned"] = true;
  d["forces"].push_back({{"type", "spring"}, {"particles", {0, 1}}, {"restLength", 0.1}, {"stiffness", 10.0}, {"damping", 0.0}});
  d["forces"].push_back({{"type", "spring"}, {"particles", {1, 2}}, {"restLength", 0.1}, {"stiffness", 10.0}, {"damping", 0.0}});
  d["forces"].push_back({{"type", "spring"}, {"particles", {2, 3}}, {"restLength", 0.1}, {"stiffness", 10.0}, {"damping", 0.0}});
  d["constraints"].push_back({{"type", "rod"}, {"particles", {1, 3}}, {"length", 0.2}});
  d["constraints"].push_back({{"type", "circular-wire"}, {"particle", 2}, {"centre", {0.2, 0.3}}, {"radius", 0.3}});
  d["collisionEdges"] = {{0, 1}, {2, 3}};
  return d;
}

// A tool's edit of the document from a gesture's points, as the App makes it.
struct ToolRun {
  Json document;
  std::optional<ObjectRef> selection;
  std::string what;
};
ToolRun runTool(const std::string& name, const Json& document, const std::vector<BuildPoint>& points,
                const Json& fields = Json()) {
  BuildMode mode;
  const std::size_t tool = *mode.toolNamed(name);
  const scenes::Scene scene = buildDocument(document);
  ToolRun run{document, std::nullopt, ""};
  const Json& toolFields = fields.is_null() ? mode.fields(tool) : fields;
  ToolContext context{run.document, *scene.system, mode.particleFields(), toolFields, 0.02, run.selection};
  run.what = buildTools()[tool].apply(context, points);
  buildDocument(run.document);  // every tool's edit reads back as a scene
  return run;
}
BuildPoint at(double x, double y) { return {{x, y}, std::nullopt, {x, y}}; }
BuildPoint on(const Json& document, int particle) {
  return {particlePosition(document, particle), particle, particlePosition(document, particle)};
}

std::vector<double> steppedState(scenes::Scene scene, int steps) {
  particles::Rk4Integrator rk4;
  for (int k = 0; k < steps; ++k) scene.system->step(rk4, scene.dt);
  const Eigen::VectorXd& x = scene.system->positions();
  const Eigen::VectorXd& v = scene.system->velocities();
  std::vector<double> state(x.data(), x.data() + x.size());
  state.insert(state.end(), v.data(), v.data() + v.size());
  return state;
}

}  // namespace

TEST(SceneDocument, DeletingAParticleTakesWhatNamesItAndRenumbersTheRest) {
  Json d = fourParticles();
  deleteObject(d, {"particles", 1});
  ASSERT_EQ(d["particles"].size(), 3u);
  // Springs 0-1 and 1-2 and the rod 1-3 named particle 1; spring 2-3 is now 1-2.
  ASSERT_EQ(d["forces"].size(), 2u);  // gravity and one spring
  EXPECT_EQ(d["forces"][1]["particles"], Json({1, 2}));
  ASSERT_EQ(d["constraints"].size(), 1u);
  EXPECT_EQ(d["constraints"][0]["type"], "circular-wire");
  EXPECT_EQ(d["constraints"][0]["particle"], 1);
  EXPECT_EQ(d["collisionEdges"], Json({{1, 2}}));
  EXPECT_EQ(buildDocument(d).system->size(), 3);
}

TEST(SceneDocument, DeletingAnObjectLeavesTheParticles) {
  Json d = fourParticles();
  deleteObject(d, {"constraints", 0});
  EXPECT_EQ(d["particles"].size(), 4u);
  EXPECT_EQ(d["constraints"].size(), 1u);
  EXPECT_THROW(deleteObject(d, {"constraints", 5}), std::invalid_argument);
  EXPECT_THROW(deleteObject(d, ObjectRef{}), std::invalid_argument);
}

TEST(SceneDocument, MovingAParticleRefitsWhatRestsOnIt) {
  Json d = fourParticles();
  d["constraints"].push_back({{"type", "line"}, {"particle", 3}, {"point", {0.3, 0.0}}, {"angle", 0.0}});
  d["forces"].push_back({{"type", "angular-spring"}, {"particles", {1, 2, 3}}, {"restAngle", 3.0}, {"stiffness", 1.0}, {"damping", 0.0}});
  moveParticle(d, 2, {0.2, 0.1});
  EXPECT_DOUBLE_EQ(d["forces"][2]["restLength"].get<double>(), std::hypot(0.1, 0.1));  // 1-2
  EXPECT_DOUBLE_EQ(d["forces"][3]["restLength"].get<double>(), std::hypot(0.1, 0.1));  // 2-3
  EXPECT_DOUBLE_EQ(d["constraints"][1]["radius"].get<double>(), 0.2);  // the wire about (0.2, 0.3)
  // The angle at 2 from arm 2→1 to arm 2→3: both arms point down, 90° apart.
  EXPECT_NEAR(d["forces"][4]["restAngle"].get<double>(), particles::kPi / 2, 1e-12);
  EXPECT_DOUBLE_EQ(d["forces"][1]["restLength"].get<double>(), 0.1);  // 0-1 is not on particle 2
  moveParticle(d, 3, {0.5, 0.2});
  EXPECT_EQ(d["constraints"][2]["point"], Json({0.5, 0.2}));
  EXPECT_DOUBLE_EQ(d["constraints"][0]["length"].get<double>(), (Eigen::Vector2d(0.5, 0.2) - Eigen::Vector2d(0.1, 0.0)).norm());
}

TEST(SceneDocument, MovingAColliderMovesItsPointsOnly) {
  Json d = emptyDocument();
  d["colliders"].push_back({{"type", "polygon"}, {"vertices", {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}}});
  d["colliders"].push_back({{"type", "halfPlane"}, {"point", {0.0, -1.0}}, {"normal", {0.0, 2.0}}});
  d["walls"] = {{{"min", {-2.0, -2.0}}, {"max", {-1.5, -1.5}}}};
  translateCollider(d, {"colliders", 0}, {0.5, -0.25});
  translateCollider(d, {"colliders", 1}, {0.5, -0.25});
  translateCollider(d, {"walls", 0}, {0.5, -0.25});
  EXPECT_EQ(d["colliders"][0]["vertices"], Json({{0.5, -0.25}, {1.5, -0.25}, {0.5, 0.75}}));
  EXPECT_EQ(d["colliders"][1]["point"], Json({0.5, -1.25}));
  EXPECT_EQ(d["colliders"][1]["normal"], Json({0.0, 2.0}));
  EXPECT_EQ(d["walls"][0]["min"], Json({-1.5, -2.25}));
  EXPECT_THROW(translateCollider(d, {"particles", 0}, {1.0, 0.0}), std::invalid_argument);
}

TEST(SceneDocument, AnEditTheReaderRefusesGetsItsOneLineMessage) {
  Json d = fourParticles();
  d["colliders"].push_back({{"type", "disc"}, {"centre", {0.3, 0.0}}, {"radius", 0.05}});
  try {
    buildDocument(d);
    FAIL() << "a particle inside a disc was accepted";
  } catch (const scenes::SceneFileError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("built scene: $.particles[3]: the particle starts inside colliders[0]", 0), 0u)
        << e.what();
  }
  setField(d, {"colliders", 0}, "centre", Json({0.3, 0.5}));
  EXPECT_NO_THROW(buildDocument(d));
  setField(d, {"colliders", 0}, "radius", Json(-1.0));
  EXPECT_THROW(buildDocument(d), scenes::SceneFileError);
  setField(d, {"colliders", 0}, "radius", Json());  // null removes a field: radius is required
  EXPECT_THROW(buildDocument(d), scenes::SceneFileError);
}

// The file saved is the runner's export of the scene the document reads as:
// read back, it is the same scene and steps bit for bit like it.
TEST(SceneDocument, TheSavedFileReadsBackToTheSameSceneBitForBit) {
  Json d = fourParticles();
  d["particles"][2]["velocity"] = {0.1 / 3.0, -2.0 / 7.0};
  moveParticle(d, 3, {0.3 + 1e-13, 1.0 / 3.0});
  const std::string text = documentFileText(d);
  const scenes::Scene fromFile = scenes::readScene(text, "saved.json");
  EXPECT_EQ(scenes::writeScene(fromFile), text);
  EXPECT_EQ(steppedState(buildDocument(d), 300), steppedState(scenes::readScene(text, "saved.json"), 300));
  EXPECT_EQ(scenes::readScene(text, "x").system->position(3), Eigen::Vector2d(0.3 + 1e-13, 1.0 / 3.0));
}

TEST(SceneDocument, AnyBuiltInSceneStartsADocumentThatReadsBackAsIt) {
  for (const scenes::SceneInfo& info : scenes::sceneTable()) {
    SCOPED_TRACE(info.name);
    const scenes::Scene scene = scenes::buildScene(info.name);
    const Json d = documentOf(scene);
    EXPECT_EQ(documentFileText(d), scenes::writeScene(scene));
  }
}

TEST(SceneDocument, FieldValuesAreJsonOrElseText) {
  EXPECT_EQ(parseFieldValue("0.5"), Json(0.5));
  EXPECT_EQ(parseFieldValue("[0, -9.81]"), Json({0, -9.81}));
  EXPECT_EQ(parseFieldValue("true"), Json(true));
  EXPECT_EQ(parseFieldValue("\"root\""), Json("root"));
  EXPECT_EQ(parseFieldValue("root"), Json("root"));
  EXPECT_EQ(parseFieldValue("my scene"), Json("my scene"));
}

TEST(EditHistory, UndoGoesBackToTheStateBeforeAndRedoToTheStateAfter) {
  EditHistory history;
  const Json before = fourParticles();
  history.reset(before, "start");
  Json after = before;
  deleteObject(after, {"particles", 2});
  history.push(after, "delete particles[2]");
  EXPECT_EQ(history.undo(), "delete particles[2]");
  EXPECT_EQ(history.current(), before);
  EXPECT_EQ(history.redo(), "delete particles[2]");
  EXPECT_EQ(history.current(), after);
  EXPECT_FALSE(history.canRedo());
  history.undo();
  Json other = before;
  moveParticle(other, 1, {0.1, 0.5});
  history.push(other, "move particles[1]");  // an edit after an undo drops the redo
  EXPECT_FALSE(history.canRedo());
  EXPECT_EQ(history.size(), 2u);
  history.undo();
  EXPECT_FALSE(history.canUndo());
  EXPECT_THROW(history.undo(), std::logic_error);
}

TEST(EditHistory, KeepsTheNewestStatesUpToItsCapacity) {
  EditHistory history(3);
  for (int k = 0; k < 5; ++k) history.push(Json(k), "edit " + std::to_string(k));
  EXPECT_EQ(history.size(), 3u);
  EXPECT_EQ(history.current(), Json(4));
  history.undo();
  history.undo();
  EXPECT_EQ(history.current(), Json(2));
  EXPECT_FALSE(history.canUndo());
}

TEST(BuildTools, ASpringDrawnInEmptySpaceAddsBothParticlesAtRest) {
  const ToolRun run = runTool("spring", emptyDocument(), {at(0.0, 0.0), at(0.3, 0.4)});
  ASSERT_EQ(run.document["particles"].size(), 2u);
  EXPECT_EQ(run.document["particles"][1]["position"], Json({0.3, 0.4}));
  EXPECT_EQ(run.document["particles"][1]["mass"], 0.1);
  const Json& spring = run.document["forces"][1];
  EXPECT_EQ(spring["type"], "spring");
  EXPECT_EQ(spring["particles"], Json({0, 1}));
  EXPECT_DOUBLE_EQ(spring["restLength"].get<double>(), 0.5);
  EXPECT_EQ(spring["stiffness"], 50.0);
  EXPECT_EQ(run.what, "add spring");
  EXPECT_EQ(run.selection, (ObjectRef{"forces", 1}));
}

TEST(BuildTools, ARodBetweenParticlesSnapsToThemAndAddsNone) {
  const Json d = fourParticles();
  const ToolRun run = runTool("rod", d, {on(d, 0), on(d, 3)});
  EXPECT_EQ(run.document["particles"].size(), 4u);
  EXPECT_EQ(run.document["constraints"][2], Json({{"type", "rod"}, {"particles", {0, 3}}, {"length", 0.1 * 3}, {"form", "squared"}}));
  EXPECT_THROW(runTool("rod", d, {on(d, 1), on(d, 1)}), std::invalid_argument);
  EXPECT_THROW(runTool("spring", d, {at(0.5, 0.5), at(0.5, 0.5)}), std::invalid_argument);
}

TEST(BuildTools, AnAngleSpringRestsAtTheAngleDrawn) {
  Json d = emptyDocument();
  for (const auto& p : {std::pair{1.0, 0.0}, std::pair{0.0, 0.0}, std::pair{0.0, 1.0}}) d["particles"].push_back(particleAt(p.first, p.second));
  const ToolRun run = runTool("angle spring", d, {on(d, 0), on(d, 1), on(d, 2)});
  EXPECT_DOUBLE_EQ(run.document["forces"][1]["restAngle"].get<double>(), particles::kPi / 2);
  EXPECT_EQ(run.document["forces"][1]["particles"], Json({0, 1, 2}));
  EXPECT_THROW(runTool("angle spring", d, {on(d, 0), on(d, 1), on(d, 0)}), std::invalid_argument);
}

TEST(BuildTools, WiresAndLinesTakeTheirShapeFromTheDrag) {
  const ToolRun wire = runTool("wire", emptyDocument(), {at(0.0, 0.0), at(0.0, -0.25)});
  EXPECT_EQ(wire.document["constraints"][0],
            Json({{"type", "circular-wire"}, {"particle", 0}, {"centre", {0.0, 0.0}}, {"radius", 0.25}}));
  const ToolRun line = runTool("line", emptyDocument(), {at(0.1, 0.1), at(0.2, 0.2)});
  EXPECT_DOUBLE_EQ(line.document["constraints"][0]["angle"].get<double>(), particles::kPi / 4);
  EXPECT_EQ(line.document["constraints"][0]["point"], Json({0.1, 0.1}));
}

TEST(BuildTools, EveryColliderKindFromItsGesture) {
  const Json e = emptyDocument();
  EXPECT_EQ(runTool("half-plane", e, {at(0, -1), at(0, -0.5)}).document["colliders"][0]["normal"], Json({0.0, 0.5}));
  const Json box = runTool("box", e, {at(0.5, -0.2), at(-0.5, 0.3)}).document["colliders"][0];  // any two corners
  EXPECT_EQ(box["min"], Json({-0.5, -0.2}));
  EXPECT_EQ(box["max"], Json({0.5, 0.3}));
  EXPECT_THROW(runTool("box", e, {at(0, 0), at(1, 0)}), std::invalid_argument);
  // Corners clicked clockwise, with one inside: the hull, counter-clockwise.
  const Json polygon =
      runTool("polygon", e, {at(0, 0), at(0, 1), at(0.2, 0.2), at(1, 1), at(1, 0)}).document["colliders"][0];
  EXPECT_EQ(polygon["vertices"], Json({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  EXPECT_THROW(runTool("polygon", e, {at(0, 0), at(1, 1), at(2, 2)}), std::invalid_argument);
  const Json capsule = runTool("capsule", e, {at(0, 0), at(1, 0)}).document["colliders"][0];
  EXPECT_EQ(capsule["radius"], 0.02);
  EXPECT_EQ(capsule["to"], Json({1, 0}));
  EXPECT_EQ(runTool("disc", e, {at(0, 0), at(0.3, 0.4)}).document["colliders"][0]["radius"], 0.5);
}

TEST(BuildTools, SelectClicksPickAndDragsMove) {
  Json d = fourParticles();
  d["colliders"].push_back({{"type", "box"}, {"min", {-1.0, -1.0}}, {"max", {1.0, -0.5}}});
  const ToolRun click = runTool("select", d, {at(0.05, 0.004), at(0.05, 0.004)});
  EXPECT_EQ(click.what, "");
  EXPECT_EQ(click.selection, (ObjectRef{"forces", 1}));  // the spring 0-1 (a collision edge lies on it too)
  const ToolRun wire = runTool("select", d, {at(0.5, 0.3), at(0.5, 0.3)});
  EXPECT_EQ(wire.selection, (ObjectRef{"constraints", 1}));  // on the wire's circle
  const ToolRun inside = runTool("select", d, {at(0.0, -0.8), at(0.0, -0.8)});
  EXPECT_EQ(inside.selection, (ObjectRef{"colliders", 0}));
  const ToolRun move = runTool("select", d, {on(d, 3), at(0.3, 0.2)});
  EXPECT_EQ(move.what, "move particles[3]");
  EXPECT_EQ(move.document["particles"][3]["position"], Json({0.3, 0.2}));
  const ToolRun slide = runTool("select", d, {at(0.0, -0.8), at(0.5, -0.8)});
  EXPECT_EQ(slide.document["colliders"][0]["min"], Json({-0.5, -1.0}));
}

TEST(BuildTools, DeleteRemovesWhatIsUnderTheClick) {
  const Json d = fourParticles();
  const ToolRun run = runTool("delete", d, {on(d, 3)});
  EXPECT_EQ(run.what, "delete particles[3]");
  EXPECT_EQ(run.document["particles"].size(), 3u);
  EXPECT_THROW(runTool("delete", d, {at(0.9, 0.9)}), std::invalid_argument);
}

TEST(BuildMode, ADragsPointsSnapToParticlesOrTheGrid) {
  const Json d = fourParticles();
  const scenes::Scene scene = buildDocument(d);
  BuildMode mode;
  mode.selectTool(*mode.toolNamed("spring"));
  mode.grid = 0.25;
  const BuildPoint press = mode.pointAt({0.105, 0.01}, *scene.system, 0.02, false);
  EXPECT_EQ(press.particle, 1);
  EXPECT_EQ(press.at, Eigen::Vector2d(0.1, 0.0));
  mode.press(press);
  const BuildPoint release = mode.pointAt({0.6, 0.4}, *scene.system, 0.02, true);
  EXPECT_FALSE(release.particle);
  EXPECT_EQ(release.at, Eigen::Vector2d(0.5, 0.5));
  const auto points = mode.release(release, 0.02);
  ASSERT_TRUE(points);
  EXPECT_EQ(points->size(), 2u);
  EXPECT_FALSE(mode.gestureInProgress());
  // The wire's centre (point 0) does not snap to a particle; its bead does.
  mode.selectTool(*mode.toolNamed("wire"));
  EXPECT_FALSE(mode.pointAt({0.1, 0.0}, *scene.system, 0.02, false).particle);
  EXPECT_TRUE(mode.pointAt({0.1, 0.0}, *scene.system, 0.02, true).particle);
}

TEST(BuildMode, APolygonClosesOnItsFirstCornerOrWithEnter) {
  const scenes::Scene scene = buildDocument(emptyDocument());
  BuildMode mode;
  mode.selectTool(*mode.toolNamed("polygon"));
  auto click = [&](double x, double y) {
    const BuildPoint p = mode.pointAt({x, y}, *scene.system, 0.05, true);
    mode.press(p);
    return mode.release(p, 0.05);
  };
  EXPECT_FALSE(click(0, 0));
  EXPECT_FALSE(click(1, 0));
  EXPECT_FALSE(click(1, 1));
  EXPECT_EQ(mode.pending().size(), 3u);
  const auto closed = click(0.01, 0.02);  // on the first corner
  ASSERT_TRUE(closed);
  EXPECT_EQ(closed->size(), 3u);
  EXPECT_FALSE(click(0, 0));
  EXPECT_FALSE(click(1, 0));
  EXPECT_EQ(mode.finishClicks()->size(), 2u);  // Enter ends it; the tool refuses two corners
  mode.selectTool(*mode.toolNamed("angle spring"));
  EXPECT_FALSE(click(0, 0));
  EXPECT_FALSE(click(1, 0));
  EXPECT_EQ(click(1, 1)->size(), 3u);  // three clicks make an angle spring
  // Enter does not end an angle spring before its third click (it handed the
  // tool one point, which it read as three).
  EXPECT_FALSE(click(0, 0));
  EXPECT_FALSE(mode.finishClicks());
  EXPECT_FALSE(click(1, 0));
  EXPECT_FALSE(mode.finishClicks());
  EXPECT_EQ(mode.pending().size(), 2u);
  EXPECT_EQ(click(1, 1)->size(), 3u);
}

TEST(BuildMode, ReleaseWithoutAPressDoesNothing) {
  const scenes::Scene scene = buildDocument(emptyDocument());
  BuildMode mode;
  mode.selectTool(*mode.toolNamed("box"));
  EXPECT_FALSE(mode.release(mode.pointAt({0, 0}, *scene.system, 0.05, true), 0.05));
}

TEST(BuildGeometry, ConvexHullIsCounterClockwiseWithoutInnerOrCollinearPoints) {
  const std::vector<Eigen::Vector2d> hull =
      convexHull({{0, 0}, {2, 0}, {1, 0}, {2, 2}, {1, 1}, {0, 2}, {0, 2}});
  ASSERT_EQ(hull.size(), 4u);
  EXPECT_EQ(hull[0], Eigen::Vector2d(0, 0));
  EXPECT_EQ(hull[1], Eigen::Vector2d(2, 0));
  EXPECT_EQ(hull[2], Eigen::Vector2d(2, 2));
  EXPECT_EQ(hull[3], Eigen::Vector2d(0, 2));
}
