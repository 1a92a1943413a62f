#include "csv_writer.h"

#include <stdexcept>

#include "particles/format.h"

namespace scenes {

CsvWriter::CsvWriter(const std::string& path, const std::string& what, const std::vector<std::string>& columns,
                     CsvFormat format)
    : path_(path), file_(path, what), format_(format), columns_(columns.size()) {
  for (const std::string& column : columns) *this << column;
  endRow();
}

CsvWriter& CsvWriter::operator<<(const std::string& cell) {
  if (cell_++) row_ += ',';
  row_ += cell;
  return *this;
}

CsvWriter& CsvWriter::operator<<(double value) {
  return *this << (format_.digits > 0 ? particles::formatGeneral(value, format_.digits) : particles::formatNumber(value));
}

CsvWriter& CsvWriter::operator<<(long long value) { return *this << std::to_string(value); }

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

}  // namespace scenes
