#pragma once
// DIR/values.csv: the values the report quotes, one `key,value` row each
// under the header `key,value` (the value quoted as RFC 4180 does where it
// holds a comma or a quote: csv_writer.h). The experiments record them (recordValue), scripts/make-report.sh
// appends the ones it measures itself, and render-report reads them back:
// this is the one reader and the one writer.
#include <map>
#include <string>

namespace lab {

// Every value in DIR/values.csv (none when the file does not exist).
std::map<std::string, std::string> readValues(const std::string& dir);

// Sets one value in DIR/values.csv, keeping the others (rows sorted by key).
void writeValue(const std::string& dir, const std::string& key, const std::string& value);

// Removes every value whose key starts with `prefix` (nothing when the file does not exist).
void removeValues(const std::string& dir, const std::string& prefix);

}  // namespace lab
