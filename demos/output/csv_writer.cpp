#include "output/csv_writer.h"

#include <stdexcept>

#include "output/format_number.h"

namespace output {

CsvWriter::CsvWriter(const std::string& path, const std::string& what, const std::vector<std::string>& columns,
                     CsvFormat format)
    : path_(path), file_(path, what), format_(format), columns_(columns.size()) {
  for (const std::string& column : columns) *this << column;
  endRow();
}

std::string csvField(const std::string& cell) {
  if (cell.find_first_of(",\"\n\r") == std::string::npos) return cell;
  std::string quoted = "\"";
  for (char c : cell) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + '"';
}

std::string csvUnquote(const std::string& field) {
  if (field.size() < 2 || field.front() != '"' || field.back() != '"') return field;
  std::string text;
  for (std::size_t k = 1; k + 1 < field.size(); ++k) {
    text += field[k];
    if (field[k] == '"' && field[k + 1] == '"') ++k;
  }
  return text;
}

std::vector<std::string> csvSplit(const std::string& row) {
  std::vector<std::string> fields;
  std::string field;
  bool quoted = false;
  for (char c : row) {
    if (c == '"') quoted = !quoted;  // a doubled quote toggles twice: csvUnquote keeps one
    if (c == ',' && !quoted) {
      fields.push_back(csvUnquote(field));
      field.clear();
    } else if (c != '\r') {
      field += c;
    }
  }
  fields.push_back(csvUnquote(field));
  return fields;
}

CsvWriter& CsvWriter::operator<<(const std::string& cell) { return append(csvField(cell)); }

// Numbers never need quoting.
CsvWriter& CsvWriter::operator<<(double value) {
  return append(format_.digits > 0 ? output::formatGeneral(value, format_.digits) : output::formatNumber(value));
}

CsvWriter& CsvWriter::operator<<(long long value) { return append(std::to_string(value)); }

CsvWriter& CsvWriter::append(const std::string& field) {
  if (cell_++) row_ += ',';
  row_ += field;
  return *this;
}

void CsvWriter::endRow() {
  if (cell_ != columns_)
    throw std::logic_error(path_ + ": row has " + std::to_string(cell_) + " cells, expected " +
                           std::to_string(columns_));
  row_ += '\n';
  file_.stream() << row_;
  if (format_.flushRows) file_.stream().flush();
  file_.check();
  row_.clear();
  cell_ = 0;
}

}  // namespace output
