// The panel's state actions: the state now saved to a scene file and loaded
// back (Save state, Load state), and the frames recorded to PNGs (Record,
// what --record does from the start).
#include <cstdio>
#include <filesystem>

#include "app.h"
#include "output/output_file.h"
#include "scene_file/scene_file.h"

namespace demo {

namespace {
// The scene file of the first pane's state now: its particles where they
// are, its clock, torn springs, wind and tearing, and the integrator, dt and
// settings it runs with; the user's mouse joint is the hand, not the scene,
// and is left out.
Json stateDocument(const Simulation& pane, const std::string& label) {
  Json document = documentOf(pane.scene());
  const auto& forces = pane.system().forceObjects();
  for (std::size_t k = forces.size(); k-- > 0;)
    if (forces[k].get() == pane.mouseSpring()) document["forces"].erase(k);
  document["name"] = label;
  document["integrator"] = pane.integratorName();
  document["integratorSettings"] = scenes::integratorSettingsToJson(pane.integratorSettings());
  document["dt"] = pane.dt();
  return document;
}
}  // namespace

void App::saveState() {
  if (stateFile_.empty()) throw std::invalid_argument("save state: the state file field is empty");
  const Simulation& pane = *panes_.front();
  char label[160];
  std::snprintf(label, sizeof label, "%s at t = %.3f s", scene_.label.c_str(), pane.system().time());
  // Through the reader and the writer, as build mode saves: what is written reads back.
  const std::string text = documentFileText(stateDocument(pane, label));
  output::OutputFile file(stateFile_, "state");  // throws, naming the file, when it cannot be written
  file.stream() << text;
  file.close();
  setStatus(std::string("saved ") + label + " to " + stateFile_ + " (Load state, or particle-demo --scene-file " +
            stateFile_ + ")");
}

void App::loadState() {
  if (stateFile_.empty()) throw std::invalid_argument("load state: the state file field is empty");
  SceneChoice choice;
  choice.file = stateFile_;
  choice.label = std::filesystem::path(stateFile_).filename().string();
  const bool keepIntegrators = false;  // the file's integrator, dt and clock
  loadScene(choice, keepIntegrators);
  setStatus("loaded " + stateFile_ + ": t = " + std::to_string(panes_.front()->system().time()).substr(0, 6) + " s");
}

// Every frame from the next on as DIR/frame-NNNNNN.png (numbered by frame),
// DIR the --record directory or particle-demo-frames.
void App::toggleRecording() {
  if (recording_) {
    recording_ = false;
    setStatus("recording stopped");
    return;
  }
  const std::string dir = recordDirectory();
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (!std::filesystem::is_directory(dir, error)) throw std::invalid_argument("record: cannot create the directory '" + dir + "'");
  recording_ = true;
  setStatus("recording every frame to " + dir + "/frame-NNNNNN.png (Stop recording ends it)");
}

std::string App::recordDirectory() const { return options_.record.empty() ? "particle-demo-frames" : options_.record; }

}  // namespace demo
