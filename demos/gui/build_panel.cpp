// The panel's Build section: build mode on and off, the tools and the fields
// of what they add, undo and redo, the file field, the selection's fields and
// a list of every object. Each control calls what its key or script event
// calls (build_actions.cpp).
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "app.h"
#include "panel_rows.h"

namespace demo {

namespace {
// Longer values (a list of particles) are edited through their objects.
constexpr std::size_t fieldTextLimit = 480;
constexpr std::size_t longListSize = 16;

// One line naming an object of a list: its type and the particles it names.
std::string describe(const ObjectRef& ref, const Json& object) {
  std::string text = ref.name();
  if (object.is_object() && object.contains("type")) text += "  " + object["type"].get<std::string>();
  const std::vector<int> named = particlesOf(ref, object);
  constexpr std::size_t shown = 8;  // a cloth's faces name hundreds
  for (std::size_t k = 0; k < named.size() && k < shown; ++k) text += (k ? "-" : "  ") + std::to_string(named[k]);
  if (named.size() > shown) text += "-... (" + std::to_string(named.size()) + " particles)";
  if (ref.list == "particles" && object.value("pinned", false)) text += "  pinned";
  return text;
}
}  // namespace

void App::drawBuildSection() {
  if (build_.active()) ImGui::SetNextItemOpen(true, ImGuiCond_Always);
  if (!ImGui::CollapsingHeader("Build", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (!build_.active()) {
    if (ImGui::Button("Build mode (e)")) guarded([&] { enterBuildMode(false); });
    recordWidget("build");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("edit the scene as it starts: add, move and delete objects, save it");
    sameLineIfFits(buttonWidth("from the state now"));
    if (ImGui::Button("from the state now")) guarded([&] { enterBuildMode(true); });
    recordWidget("build-now");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("edit the scene as it is now: positions and velocities at this time");
    return;
  }
  if (ImGui::Button("Run the scene (e)")) guarded([&] { leaveBuildMode(); });
  recordWidget("build");
  drawBuildTools();
  drawBuildHistory();
  drawBuildFile();
  drawBuildSelection();
  drawBuildObjectList();
}

// The tools, two to a row, the one in hand's gesture and the fields of what it adds.
void App::drawBuildTools() {
  const std::vector<BuildTool>& tools = buildTools();
  const float column = 0.5f * ImGui::GetContentRegionAvail().x;
  for (std::size_t k = 0; k < tools.size(); ++k) {
    char label[48];
    std::snprintf(label, sizeof label, "%s (%c)", tools[k].name, tools[k].key);
    if (k % 2 != 0) ImGui::SameLine(column);
    if (ImGui::RadioButton(label, build_.toolIndex() == k)) guarded([&] { chooseBuildTool(k); });
  }
  ImGui::TextWrapped("%s", build_.tool().help);
  if (ImGui::TreeNode("other keys")) {
    for (const KeyBinding& binding : buildKeyBindings()) ImGui::BulletText("%s  %s", binding.label, binding.help);
    ImGui::BulletText("Esc, right click  cancel the gesture, then the selection");
    ImGui::TreePop();
  }
  drawBuildFields("new", build_.fields(build_.toolIndex()));
  double grid = build_.grid;
  if (ImGui::InputDouble("grid", &grid, 0.0, 0.0, "%g", ImGuiInputTextFlags_EnterReturnsTrue))
    guarded([&] { editBuildField("build", "grid", Json(grid).dump()); });
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("points off particles snap to multiples of this (0: off)");
}

// Every field of an object (of the scene when target is "selected" and none
// is), each applied with Enter; a value the scene file refuses is shown as
// an error and changes nothing.
void App::drawBuildFields(const char* target, const Json& object) {
  ImGui::PushID(target);
  for (const auto& item : object.items()) {
    const std::string& key = item.key();  // named, not a structured binding: lambdas capture it
    const Json& value = item.value();
    if (key == "type") continue;
    ImGui::PushID(key.c_str());
    if (value.is_boolean()) {
      bool on = value.get<bool>();
      if (ImGui::Checkbox(key.c_str(), &on)) guarded([&] { editBuildField(target, key, on ? "true" : "false"); });
    } else {
      const bool long_ = value.is_array() && value.size() > longListSize;  // not printed every frame
      const std::string text = long_ ? "" : value.is_string() ? value.get<std::string>() : value.dump();
      if (long_ || text.size() > fieldTextLimit) {
        ImGui::TextDisabled("%s: %zu entries", key.c_str(), value.size());
        ImGui::PopID();
        continue;
      }
      char buffer[fieldTextLimit + 32];
      std::snprintf(buffer, sizeof buffer, "%s", text.c_str());
      if (ImGui::InputText(key.c_str(), buffer, sizeof buffer, ImGuiInputTextFlags_EnterReturnsTrue))
        guarded([&] { editBuildField(target, key, buffer); });
    }
    ImGui::PopID();
  }
  ImGui::PopID();
}

void App::drawBuildHistory() {
  const EditHistory& history = build_.history;
  ImGui::BeginDisabled(!history.canUndo());
  if (ImGui::Button("Undo (z)")) guarded([&] { undoBuild(); });
  recordWidget("build-undo");
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled) && history.canUndo())
    ImGui::SetTooltip("undo %s", history.nextUndo().c_str());
  ImGui::EndDisabled();
  sameLineIfFits(buttonWidth("Redo (y)"));
  ImGui::BeginDisabled(!history.canRedo());
  if (ImGui::Button("Redo (y)")) guarded([&] { redoBuild(); });
  recordWidget("build-redo");
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled) && history.canRedo())
    ImGui::SetTooltip("redo %s", history.nextRedo().c_str());
  ImGui::EndDisabled();
  sameLineIfFits(buttonWidth("New (N)"));
  if (ImGui::Button("New (N)")) guarded([&] { newBuild(); });
  recordWidget("build-new");
  ImGui::TextDisabled("%zu of %zu states", history.position() + 1, history.size());
}

void App::drawBuildFile() {
  char buffer[1024];
  std::snprintf(buffer, sizeof buffer, "%s", build_.file.c_str());
  if (ImGui::InputText("file", buffer, sizeof buffer)) build_.file = buffer;
  recordWidget("build-file");
  if (ImGui::Button("Save (s)")) guarded([&] { saveBuild(); });
  recordWidget("build-save");
  sameLineIfFits(buttonWidth("Open (o)"));
  if (ImGui::Button("Open (o)")) guarded([&] { openBuild(); });
  recordWidget("build-open");
}

void App::drawBuildSelection() {
  const Json& document = build_.history.current();
  const std::optional<ObjectRef>& selected = build_.selection;
  ImGui::Separator();
  if (!selected) {
    ImGui::Text("the scene's fields (nothing selected)");
    drawBuildFields("selected", document);
    return;
  }
  if (!refersToObject(document, *selected)) return;
  ImGui::Text("%s", describe(*selected, objectAt(document, *selected)).c_str());
  sameLineIfFits(buttonWidth("delete"));
  if (ImGui::SmallButton("delete")) guarded([&] { deleteBuildSelection(); });
  recordWidget("build-delete");
  const Json& object = objectAt(document, *selected);
  if (object.is_object()) drawBuildFields("selected", object);
}

// Every object by list; a click selects it (the only way to reach gravity or drag).
void App::drawBuildObjectList() {
  const Json& document = build_.history.current();
  if (!ImGui::TreeNode("objects")) return;
  if (ImGui::Selectable("scene", !build_.selection)) guarded([&] { selectBuildObject(std::nullopt); });
  for (const char* list : {"particles", "forces", "constraints", "colliders", "walls", "collisionEdges"}) {
    const auto found = document.find(list);
    if (found == document.end() || !found->is_array() || found->empty()) continue;
    char label[64];
    std::snprintf(label, sizeof label, "%s (%zu)", list, found->size());
    if (!ImGui::TreeNode(label)) continue;
    ImGuiListClipper clipper;
    clipper.Begin(static_cast<int>(found->size()));
    while (clipper.Step())
      for (int k = clipper.DisplayStart; k < clipper.DisplayEnd; ++k) {
        const ObjectRef ref{list, static_cast<std::size_t>(k)};
        if (ImGui::Selectable(describe(ref, (*found)[static_cast<std::size_t>(k)]).c_str(), build_.selection == ref))
          guarded([&] { selectBuildObject(ref); });
      }
    ImGui::TreePop();
  }
  ImGui::TreePop();
}

}  // namespace demo
