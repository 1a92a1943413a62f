// particle-lab list: the scenes with their parameters and defaults, and the integrators.
#include <iomanip>
#include <iostream>

#include "cli/command.h"
#include "particles/integrator.h"
#include "scene.h"

namespace cli {

namespace {
int list() {
  std::cout << "scenes (particle-lab run --scene NAME --param key=value ...):\n";
  for (const scenes::SceneInfo& info : scenes::sceneTable()) {
    std::cout << "  " << std::left << std::setw(12) << info.name << info.summary << '\n';
    for (const scenes::ParamSpec& p : info.params)
      std::cout << "      " << std::setw(22) << (p.name + "=" + p.defaultValue) << p.help << '\n';
  }
  std::cout << "integrators (--integrator NAME):\n";
  for (const particles::IntegratorInfo& info : particles::integratorTable())
    std::cout << "  " << std::setw(18) << info.name << "order " << info.order << ": " << info.summary << '\n';
  return kSuccess;
}
}  // namespace

Command addListCommand(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("list", "list the built-in scenes with their parameters and defaults, and the integrators");
  return {sub, list};
}

}  // namespace cli
