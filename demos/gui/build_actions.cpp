// Build mode's actions (its state is build_mode.h): entering and leaving it,
// its keys and mouse, committing edits, undo and redo, saving and opening
// scene files.
#include <GL/freeglut.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "app.h"
#include "output/output_file.h"
#include "scene_file/scene_file.h"
#ifdef __EMSCRIPTEN__
#include "page.h"
#endif

namespace demo {

namespace {
// Keys that act on a running simulation: in build mode they wait for it to run.
constexpr const char* runningKeys = "i+=-_.rbvl";

// The scene choice of a document: what r, compare mode and the advice rebuild.
SceneChoice documentChoice(const Json& document) {
  SceneChoice choice;
  choice.label = documentName(document);
  choice.document = std::make_shared<const Json>(document);
  return choice;
}
// A grid spacing as typed: a finite number >= 0 (0: no grid).
double gridSpacing(const std::string& text) {
  const Json value = parseFieldValue(text);
  if (!value.is_number() || !std::isfinite(value.get<double>()) || value.get<double>() < 0.0)
    throw std::invalid_argument("grid: expected a number >= 0 (0: no grid), got " + text);
  return value.get<double>();
}
}  // namespace

const std::vector<App::KeyBinding>& App::buildKeyBindings() {
  static const std::vector<KeyBinding> table = {
      {"z\x1a", "z", "undo", &App::undoBuild},
      {"y\x19", "y", "redo", &App::redoBuild},
      {"s", "s", "save the scene to the file field's path", &App::saveBuild},
      {"o", "o", "open the file field's scene file", &App::openBuild},
      {"N", "N", "start a new, empty scene", &App::newBuild},
      {"\x7f\x08", "Delete", "delete the selection", &App::deleteBuildSelection},
      {"\r", "Enter", "close a polygon", &App::finishBuildClicks},
  };
  return table;
}

// --- entering and leaving ---------------------------------------------------------

void App::toggleBuildMode() {
  if (build_.active()) leaveBuildMode();
  else enterBuildMode(false);
}

void App::enterBuildMode(bool currentState) {
  Simulation& pane = *panes_.front();
  pane.release();  // the mouse joint is the user's hand, not part of the scene
  Json document = currentState ? documentOf(pane.scene()) : documentOf(buildChoice(scene_));
  // What runs is what is built and saved: the pane's integrator, dt and settings.
  const particles::IntegratorSettings& settings = pane.integratorSettings();
  document["integrator"] = pane.integratorName();
  document["integratorSettings"] = scenes::integratorSettingsToJson(settings);
  document["dt"] = pane.dt();
  // Build mode starts only once the reader has taken the document (a state
  // dragged into a wall is refused with the reader's message, and the panes
  // run on as they were); the built scene replaces every pane.
  startBuildFrom(std::move(document), "start from " + scene_.label + (currentState ? " as it is" : ""));
  build_.setActive(true);
  setStatus("build mode: " + std::string(build_.tool().name) + " (" + build_.tool().help + "); e runs the scene");
}

void App::leaveBuildMode() {
  build_.setActive(false);
  sceneHint_.clear();
  paused_ = false;
  setStatus("running " + scene_.label + " (e builds again)");
}

void App::startBuildFrom(Json document, const std::string& what) {
  scenes::Scene scene = buildDocument(document);  // throws before anything changes
  if (build_.history.empty() || build_.history.current() != document) build_.history.push(std::move(document), what);
  build_.selection.reset();
  build_.cancelGesture();
  showBuiltScene(std::move(scene));
}

// --- the scene on screen ----------------------------------------------------------

void App::showBuildDocument() { showBuiltScene(buildDocument(build_.history.current())); }

void App::showBuiltScene(scenes::Scene scene) {
  const int integrator = integratorIndexByName(scene.integrator);
  const double dt = scene.dt;
  const particles::IntegratorSettings settings = scene.integratorSettings;
  std::vector<std::unique_ptr<Simulation>> panes;
  panes.push_back(std::make_unique<Simulation>(std::move(scene), integrator, dt));
  panes.front()->setIntegratorSettings(settings);
  replacePanes(std::move(panes));
  scene_ = documentChoice(build_.history.current());
  exact_ = {};
  showBuildHint();
}

void App::commitBuild(Json document, const std::string& what) {
  scenes::Scene scene = buildDocument(document);  // a refused edit changes nothing
  build_.history.push(std::move(document), what);
  showBuiltScene(std::move(scene));
  setStatus(what);
}

void App::chooseBuildTool(std::size_t tool) {
  build_.selectTool(tool);
  showBuildHint();
  setStatus(std::string("tool: ") + build_.tool().name + " (" + build_.tool().help + ")");
}

// The top bar's standing line in build mode: the tool in hand and its gesture.
void App::showBuildHint() {
  sceneHint_ = std::string("build mode, ") + build_.tool().name + ": " + build_.tool().help + "   (e runs the scene)";
  hintUntilFrame_ = std::numeric_limits<long long>::max();
}

double App::buildPickRadius() const { return mouseSettings_.pickPixels / paneViews().front().pixelsPerUnit; }

// --- keys and mouse --------------------------------------------------------------

bool App::buildKeyboard(unsigned char key) {
  if (const std::optional<std::size_t> tool = build_.toolForKey(key)) {
    chooseBuildTool(*tool);
    return true;
  }
  for (const KeyBinding& binding : buildKeyBindings())
    if (key != 0 && std::strchr(binding.keys, key)) {
      (this->*binding.action)();
      return true;
    }
  if (key == 27 && (build_.gestureInProgress() || build_.selection)) {  // Esc: cancel, then deselect
    if (build_.gestureInProgress()) build_.cancelGesture();
    else build_.selection.reset();
    return true;
  }
  if (key != 0 && std::strchr(runningKeys, key)) {
    setStatus("build mode: the scene stays at t = 0 while it is built; e runs it");
    return true;
  }
  return false;
}

bool App::buildMouse(int button, int state, int x, int y) {
  // The camera's: a middle drag, space + left drag. Every other press is
  // build mode's, so that no tool of the running scene (a pin) acts on it.
  if (panning_ || button == GLUT_MIDDLE_BUTTON || (spaceHeld_ && button == GLUT_LEFT_BUTTON)) return false;
  if (button == GLUT_RIGHT_BUTTON) {  // cancels a gesture, then the selection
    if (state == GLUT_DOWN && build_.gestureInProgress()) build_.cancelGesture();
    else if (state == GLUT_DOWN) build_.selection.reset();
    return true;
  }
  if (button != GLUT_LEFT_BUTTON) return true;
  const ViewTransform view = paneViews().front();
  if (state == GLUT_DOWN && !view.pane.contains(x, y)) return true;
  const Eigen::Vector2d world = view.toWorld(x, y);
  const double radius = buildPickRadius();
  const particles::ParticleSystem& system = panes_.front()->system();
  if (state == GLUT_DOWN) {
    build_.press(build_.pointAt(world, system, radius, false));
    return true;
  }
  if (const auto points = build_.release(build_.pointAt(world, system, radius, true), radius)) runBuildTool(*points);
  return true;
}

void App::buildMotion(int x, int y) { build_.moveTo(paneViews().front().toWorld(x, y)); }

void App::runBuildTool(const std::vector<BuildPoint>& points) {
  Json next = build_.history.current();
  std::optional<ObjectRef> selection = build_.selection;
  const std::size_t tool = build_.toolIndex();
  ToolContext context{next, panes_.front()->system(), build_.particleFields(), build_.fields(tool), buildPickRadius(),
                      selection};
  const std::string what = build_.tool().apply(context, points);
  if (!what.empty()) commitBuild(std::move(next), what);  // throws when refused: nothing changes
  build_.selection = selection;
  if (what.empty()) setStatus(selection ? "selected " + selection->name() : "nothing here to select");
}

void App::finishBuildClicks() {
  if (const auto points = build_.finishClicks()) runBuildTool(*points);
}

// --- fields, selection and script ----------------------------------------------------

void App::editBuildField(const std::string& target, const std::string& field, const std::string& text) {
  if (target == "build") {
    if (field == "file") build_.file = text;
    else if (field == "grid") build_.grid = gridSpacing(text);
    else throw std::invalid_argument("build has the fields grid and file, not '" + field + "'");
    return;
  }
  if (target == "new") {
    Json& fields = build_.fields(build_.toolIndex());
    const Json value = parseFieldValue(text);
    if (!fields.contains(field) || fields[field].type_name() != std::string(value.type_name()))
      throw std::invalid_argument(std::string("the ") + build_.tool().name + " tool has no " + value.type_name() +
                                  " field '" + field + "' (its fields: " + fields.dump() + ")");
    fields[field] = value;
    return;
  }
  const ObjectRef ref = build_.selection.value_or(ObjectRef{});
  Json next = build_.history.current();
  setField(next, ref, field, parseFieldValue(text));
  commitBuild(std::move(next), "set " + ref.name() + "." + field + " = " + text);
}

void App::selectBuildObject(const std::optional<ObjectRef>& ref) {
  if (ref && !refersToObject(build_.history.current(), *ref))
    throw std::invalid_argument("select: the scene has no " + ref->name());
  build_.selection = ref && !ref->isScene() ? ref : std::nullopt;
  setStatus(build_.selection ? "selected " + build_.selection->name() : "selected the scene");
}

void App::scriptBuildEvent(const ScriptEvent& e) {
  if (!build_.active()) throw std::invalid_argument("select and edit act in build mode (e enters it)");
  if (e.action == ScriptAction::Select)
    selectBuildObject(e.target.empty() ? std::nullopt
                                       : std::optional<ObjectRef>(ObjectRef{e.target, static_cast<std::size_t>(e.clicks)}));
  else
    editBuildField(e.target, e.field, e.text);
}

// --- history, files --------------------------------------------------------------

void App::undoBuild() {
  if (!build_.history.canUndo()) return setStatus("nothing to undo");
  const std::string what = build_.history.undo();
  build_.selection.reset();
  build_.cancelGesture();
  showBuildDocument();
  setStatus("undid " + what);
}

void App::redoBuild() {
  if (!build_.history.canRedo()) return setStatus("nothing to redo");
  const std::string what = build_.history.redo();
  build_.selection.reset();
  build_.cancelGesture();
  showBuildDocument();
  setStatus("redid " + what);
}

void App::newBuild() {
  startBuildFrom(emptyDocument(), "new scene");
  camera_.reset(panes_.front()->scene().viewMin, panes_.front()->scene().viewMax);
  setStatus("new, empty scene: add particles (n), springs (k), rods (d), ...");
}

void App::deleteBuildSelection() {
  if (!build_.selection) return setStatus("nothing selected to delete");
  Json next = build_.history.current();
  deleteObject(next, *build_.selection);
  commitBuild(std::move(next), "delete " + build_.selection->name());
  build_.selection.reset();
}

void App::saveBuild() {
  if (build_.file.empty()) throw std::invalid_argument("save: the file field is empty");
  const std::string text = documentFileText(build_.history.current());
  output::OutputFile file(build_.file, "scene");  // throws, naming the file, when it cannot be written
  file.stream() << text;
  file.close();
#ifdef __EMSCRIPTEN__
  web::offerDownload(build_.file, "application/json");  // the page's files live in memory
#endif
  setStatus("saved " + build_.file + " (particle-lab run --scene-file " + build_.file + ")");
}

void App::openBuild() {
  if (build_.file.empty()) throw std::invalid_argument("open: the file field is empty");
  const scenes::Scene scene = scenes::loadSceneFile(build_.file);  // one line naming what is wrong
  startBuildFrom(documentOf(scene), "open " + build_.file);
  camera_.reset(panes_.front()->scene().viewMin, panes_.front()->scene().viewMax);
  setStatus("opened " + build_.file);
}

}  // namespace demo
