#include "lab/render.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "lab/text_checks.h"
#include "lab/values.h"
#include "output/output_file.h"

namespace lab {

namespace {

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

std::string renderTemplate(const std::string& text, const std::string& dataDir) {
  const auto values = readValues(dataDir);
  std::string out;
  std::vector<std::string> contradictions;
  std::size_t at = 0;
  while (true) {
    const std::size_t open = text.find("{{", at);
    if (open == std::string::npos) break;
    const std::size_t close = text.find("}}", open);
    if (close == std::string::npos) throw std::runtime_error("unclosed {{ in template");
    out += text.substr(at, open - at);
    const std::string field = text.substr(open + 2, close - open - 2);
    const auto colon = field.find(':');
    const std::string kind = field.substr(0, colon), name = colon == std::string::npos ? "" : field.substr(colon + 1);
    if (kind == "table") {
      std::string table = readFile(dataDir + "/" + name + ".md");
      while (!table.empty() && table.back() == '\n') table.pop_back();
      out += table;
    } else if (kind == "value") {
      const auto found = values.find(name);
      if (found == values.end()) throw std::runtime_error("no value '" + name + "' in " + dataDir + "/values.csv");
      out += found->second;
    } else if (kind == "check") {
      const std::string broken = evaluateCheck(name, dataDir);
      if (!broken.empty()) {
        const long line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(open), '\n');
        contradictions.push_back("template line " + std::to_string(line) + ": {{check:" + name + "}} fails: " + broken);
      }
    } else {
      throw std::runtime_error("unknown template field '{{" + field + "}}'");
    }
    at = close + 2;
  }
  out += text.substr(at);
  for (const std::string& found : proseContradictions(out, dataDir)) contradictions.push_back(found);
  if (!contradictions.empty()) throw ReportContradiction(contradictions);
  return out;
}

std::string sectionBegin(const std::string& name) {
  return "<!-- begin " + name + ": rendered by scripts/make-report.sh from report/data; edit its template -->\n";
}

std::string sectionEnd(const std::string& name) { return "<!-- end " + name + " -->\n"; }

namespace {

// outPath's text with the section between its markers replaced by `rendered`.
std::string spliceSection(const std::string& file, const std::string& name, const std::string& rendered) {
  const std::string text = readFile(file), begin = sectionBegin(name), end = sectionEnd(name);
  const std::size_t open = text.find(begin);
  const std::size_t close = open == std::string::npos ? open : text.find(end, open + begin.size());
  if (close == std::string::npos)
    throw std::runtime_error(file + " has no section '" + name + "' (the lines " + begin.substr(0, begin.size() - 1) +
                             " ... " + end.substr(0, end.size() - 1) + ")");
  return text.substr(0, open + begin.size()) + rendered + text.substr(close);
}

// 1-based number of the first line where a and b differ.
std::size_t firstDifferentLine(const std::string& a, const std::string& b) {
  std::size_t line = 1;
  for (std::size_t k = 0; k < a.size() && k < b.size() && a[k] == b[k]; ++k)
    if (a[k] == '\n') ++line;
  return line;
}

// The first image the text shows that is missing beside `outPath` or shown
// twice, as a message; empty when every image exists once.
std::string figureProblem(const std::string& text, const std::string& outPath) {
  const std::string base = std::filesystem::path(outPath).parent_path().string();
  std::set<std::string> seen;
  for (std::size_t at = text.find("]("); at != std::string::npos; at = text.find("](", at + 2)) {
    const std::size_t open = text.rfind('[', at);
    if (open == std::string::npos || open == 0 || text[open - 1] != '!') continue;  // a link, not an image
    const std::size_t close = text.find(')', at);
    const std::string target = text.substr(at + 2, close - at - 2);
    if (target.find("://") != std::string::npos) continue;
    if (!seen.insert(target).second) return "shows " + target + " twice";
    if (!std::filesystem::exists(std::filesystem::path(base.empty() ? "." : base) / target))
      return "shows " + target + ", which does not exist";
  }
  return "";
}

}  // namespace

int renderReport(const RenderOptions& options) {
  std::string rendered;
  try {
    rendered = renderTemplate(readFile(options.templatePath), options.dataDir);
  } catch (const ReportContradiction& e) {
    for (const std::string& found : e.found)
      std::fprintf(stderr, "render-report: %s contradicts %s: %s\n", options.templatePath.c_str(),
                   options.dataDir.c_str(), found.c_str());
    return 1;
  }
  if (!options.section.empty()) rendered = spliceSection(options.outPath, options.section, rendered);
  if (const std::string problem = figureProblem(rendered, options.outPath); !problem.empty()) {
    std::fprintf(stderr, "render-report: %s %s\n", options.outPath.c_str(), problem.c_str());
    return 1;
  }
  if (options.check) {
    const std::string current = readFile(options.outPath);
    if (current == rendered) return 0;
    std::fprintf(stderr, "render-report: %s differs from %s rendered with %s at line %zu: edit the template, not the output\n",
                 options.outPath.c_str(), options.templatePath.c_str(), options.dataDir.c_str(),
                 firstDifferentLine(current, rendered));
    return 1;
  }
  output::OutputFile out(options.outPath, "the rendered report");
  out.stream() << rendered;
  out.close();
  return 0;
}

}  // namespace lab
