#include "lab/values.h"

#include <fstream>

#include "output/csv_writer.h"
#include "output/output_file.h"

namespace lab {

std::map<std::string, std::string> readValues(const std::string& dir) {
  std::map<std::string, std::string> values;
  std::ifstream in(dir + "/values.csv");
  std::string row;
  while (std::getline(in, row)) {
    const auto comma = row.find(',');
    if (comma != std::string::npos && row.substr(0, comma) != "key")  // not the header
      values[row.substr(0, comma)] = output::csvUnquote(row.substr(comma + 1));
  }
  return values;
}

namespace {

void writeValues(const std::string& dir, const std::map<std::string, std::string>& values) {
  output::OutputFile out(dir + "/values.csv", "the values");
  out.stream() << "key,value\n";
  for (const auto& [k, v] : values) out.stream() << k << ',' << output::csvField(v) << '\n';
  out.close();
}

}  // namespace

void writeValue(const std::string& dir, const std::string& key, const std::string& value) {
  std::map<std::string, std::string> values = readValues(dir);
  values[key] = value;
  writeValues(dir, values);
}

void removeValues(const std::string& dir, const std::string& prefix) {
  std::map<std::string, std::string> values = readValues(dir);
  std::size_t removed = 0;
  for (auto v = values.begin(); v != values.end();)
    if (v->first.rfind(prefix, 0) == 0) v = values.erase(v), ++removed;
    else ++v;
  if (removed > 0) writeValues(dir, values);
}

}  // namespace lab
