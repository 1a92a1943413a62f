#pragma once
// Fills the report template: {{table:NAME}} becomes DATA/NAME.md and
// {{value:KEY}} the value recorded under KEY in DATA/values.csv. A missing
// table or key is an error, so the report never shows a number the
// experiments did not produce.
#include <string>

namespace lab {

struct RenderOptions {
  std::string templatePath, dataDir, outPath;
};

int renderReport(const RenderOptions& options);

// The substitution itself, for tests: returns the rendered text.
std::string renderTemplate(const std::string& text, const std::string& dataDir);

}  // namespace lab
