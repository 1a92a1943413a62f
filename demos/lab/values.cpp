#include "lab/values.h"

#include <fstream>

#include "csv_writer.h"
#include "output_file.h"

namespace lab {

std::map<std::string, std::string> readValues(const std::string& dir) {
  std::map<std::string, std::string> values;
  std::ifstream in(dir + "/values.csv");
  std::string row;
  while (std::getline(in, row)) {
    const auto comma = row.find(',');
    if (comma != std::string::npos && row.substr(0, comma) != "key")  // not the header
      values[row.substr(0, comma)] = scenes::csvUnquote(row.substr(comma + 1));
  }
  return values;
}

void writeValue(const std::string& dir, const std::string& key, const std::string& value) {
  std::map<std::string, std::string> values = readValues(dir);
  values[key] = value;
  scenes::OutputFile out(dir + "/values.csv", "the values");
  out.stream() << "key,value\n";
  for (const auto& [k, v] : values) out.stream() << k << ',' << scenes::csvField(v) << '\n';
  out.close();
}

}  // namespace lab
