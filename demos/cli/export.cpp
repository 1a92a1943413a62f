// particle-lab export: writes a scene as a JSON scene file.
#include <iostream>
#include <memory>

#include "cli/command.h"
#include "options/scene_source.h"
#include "output/output_file.h"
#include "scene_file/scene_file.h"

namespace cli {

namespace {
struct ExportOptions {
  options::SceneSource source;
  std::string output;  // empty: stdout
};

int exportScene(const ExportOptions& o) {
  const std::string json = scenes::writeScene(o.source.load());
  if (o.output.empty()) {
    std::cout << json << std::flush;
    if (!std::cout) output::throwWriteError("the standard output", "-");
    return kSuccess;
  }
  output::OutputFile out(o.output, "--output");
  out.stream() << json;
  out.close();
  return kSuccess;
}
}  // namespace

Command addExportCommand(CLI::App& app) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* sub = app.add_subcommand("export", "write a scene (with its parameters applied) as a JSON scene file");
  options->source.addOptions(*sub);
  sub->add_option("-o,--output", options->output, "file to write (default: stdout)");
  return {sub, [options](const Context&) { return exportScene(*options); }};
}

}  // namespace cli
