#pragma once
// Fills the report template: {{table:NAME}} becomes DATA/NAME.md and
// {{value:KEY}} the value recorded under KEY in DATA/values.csv. A missing
// table or key is an error, so the report never shows a number the
// experiments did not produce. {{check:...}} holds a sentence against the
// data (text_checks.h) and renders as nothing; a check that fails, or prose
// the data contradicts, fails the rendering and --check alike.
#include <string>

namespace lab {

struct RenderOptions {
  std::string templatePath, dataDir, outPath;
  // With a section name, the rendered text replaces what lies between the
  // lines sectionBegin(name) and sectionEnd(name) of outPath, and the rest of
  // that file is kept (the results in the top-level README).
  std::string section;
  // Compare instead of writing: 0 when outPath already holds the rendering,
  // 1 (naming the first line that differs) when it does not.
  bool check = false;
};

std::string sectionBegin(const std::string& name);
std::string sectionEnd(const std::string& name);

int renderReport(const RenderOptions& options);

// The substitution itself, for tests: returns the rendered text; throws
// ReportContradiction (text_checks.h) listing every contradiction found.
std::string renderTemplate(const std::string& text, const std::string& dataDir);

}  // namespace lab
