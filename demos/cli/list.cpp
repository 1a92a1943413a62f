// particle-lab list: the presets, the scenes with their parameters under every
// preset, and the integrators.
#include <iomanip>
#include <iostream>

#include "cli/command.h"
#include "particles/integrator.h"
#include "scene.h"

namespace cli {

namespace {
constexpr int kNameWidth = 16, kValueWidth = 10;

int list() {
  const std::vector<scenes::PresetInfo>& presets = scenes::presetTable();
  std::cout << "presets (--preset NAME; the first is the default):\n";
  for (const scenes::PresetInfo& preset : presets)
    std::cout << "  " << std::left << std::setw(kNameWidth - 2) << preset.name << preset.summary << '\n';
  std::cout << "scenes (particle-lab run --scene NAME [--preset NAME] --param key=value ...):\n";
  for (const scenes::SceneInfo& info : scenes::sceneTable()) {
    std::cout << "  " << std::left << std::setw(12) << info.name << (std::string(info.name).size() < 12 ? "" : " ")
              << info.summary << '\n';
    std::cout << "      " << info.hint << '\n';
    std::cout << "      " << std::setw(kNameWidth) << "parameter";
    for (const scenes::PresetInfo& preset : presets) std::cout << std::setw(kValueWidth) << preset.name << ' ';
    std::cout << '\n';
    for (const scenes::ParamSpec& p : info.params) {
      std::cout << "      " << std::setw(kNameWidth) << p.name;
      for (const std::string& value : p.values) std::cout << std::setw(kValueWidth) << value << ' ';
      std::cout << p.help << '\n';
    }
    // The step each preset runs the scene with (--dt overrides it).
    std::cout << "      " << std::setw(kNameWidth) << "(dt)";
    for (const scenes::PresetInfo& preset : presets)
      std::cout << std::setw(kValueWidth) << scenes::buildScene(info.name, {}, preset.name).dt << ' ';
    std::cout << "time step, s (set by --dt)\n";
  }
  std::cout << "integrators (--integrator NAME):\n";
  for (const particles::IntegratorInfo& info : particles::integratorTable())
    std::cout << "  " << std::setw(18) << info.name << "order " << info.order << ": " << info.summary << '\n';
  return kSuccess;
}
}  // namespace

Command addListCommand(CLI::App& app) {
  CLI::App* sub = app.add_subcommand(
      "list", "list the presets, the built-in scenes with their parameters under every preset, and the integrators");
  return {sub, [](const Context&) { return list(); }};
}

}  // namespace cli
