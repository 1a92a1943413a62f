#pragma once
// The one CSV writer of the tools (the runner's --csv and --trajectory, the
// laboratory's files): a header, then rows of cells separated by commas (RFC
// 4180 quoting where a cell needs it: csvField), every
// write checked through OutputFile (a full disk is one line, exit 4) and each
// row's cell count checked against the header.
#include <string>
#include <vector>

#include "output/output_file.h"

namespace output {

// A cell as RFC 4180 writes it: as it is, or in double quotes (inner quotes
// doubled) when it holds a comma, a quote or a line break.
std::string csvField(const std::string& cell);
// The text of one field as csvField wrote it, quoted or not.
std::string csvUnquote(const std::string& field);
// The fields of one row as CsvWriter wrote it (a comma inside quotes is text), each unquoted.
std::vector<std::string> csvSplit(const std::string& row);

struct CsvFormat {
  int digits = 0;           // significant digits of a number; 0: the shortest text that reads back exactly
  bool flushRows = false;   // flush after every row, so an interrupted writer keeps its finished rows
};

class CsvWriter {
 public:
  // Creates or empties `path` and writes the header; `what` names the file in
  // errors ("--csv", "the CSV"). Throws as OutputFile does.
  CsvWriter(const std::string& path, const std::string& what, const std::vector<std::string>& columns,
            CsvFormat format = {});
  CsvWriter& operator<<(const std::string& cell);
  CsvWriter& operator<<(const char* cell) { return *this << std::string(cell); }
  CsvWriter& operator<<(double value);
  CsvWriter& operator<<(long long value);
  CsvWriter& operator<<(long value) { return *this << static_cast<long long>(value); }
  CsvWriter& operator<<(int value) { return *this << static_cast<long long>(value); }
  // Ends the row; throws std::logic_error when it has the wrong number of
  // cells, WriteError when a write failed.
  void endRow();
  // Flushes and closes; throws WriteError when that or any write failed.
  void close() { file_.close(); }
  const std::string& path() const { return path_; }

 private:
  CsvWriter& append(const std::string& field);  // a field as written (quoted already if it must be)

  std::string path_;
  OutputFile file_;
  CsvFormat format_;
  std::size_t columns_, cell_ = 0;
  std::string row_;
};

}  // namespace output
