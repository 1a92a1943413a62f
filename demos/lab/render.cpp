#include "lab/render.h"

#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "lab/values.h"
#include "output_file.h"

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
    } else {
      throw std::runtime_error("unknown template field '{{" + field + "}}'");
    }
    at = close + 2;
  }
  return out + text.substr(at);
}

int renderReport(const RenderOptions& options) {
  const std::string rendered = renderTemplate(readFile(options.templatePath), options.dataDir);
  scenes::OutputFile out(options.outPath, "the rendered report");
  out.stream() << rendered;
  out.close();
  return 0;
}

}  // namespace lab
