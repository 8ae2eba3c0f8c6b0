#include "export/csv.h"

#include <cmath>
#include <cstdio>

#include "geometry/atomic_file.h"
#include "geometry/errors.h"

namespace windplan {

std::string format_csv_number(double v, int digits) {
  if (!std::isfinite(v)) return "nan";
  if (v == std::floor(v) && std::fabs(v) < 1e15) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f", v);
    return buf[0] == '-' && std::string(buf) == "-0" ? "0" : buf;
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

void write_csv(std::ostream& out, const CsvTable& table) {
  for (std::size_t i = 0; i < table.header.size(); ++i) {
    out << (i ? "," : "") << table.header[i];
  }
  out << "\n";
  for (const auto& row : table.rows) {
    if (row.size() != table.header.size()) {
      throw InvariantError("CSV row has " + std::to_string(row.size()) + " values for " +
                           std::to_string(table.header.size()) + " columns");
    }
    for (std::size_t i = 0; i < row.size(); ++i) {
      out << (i ? "," : "") << format_csv_number(row[i], table.digits);
    }
    out << "\n";
  }
}

void write_csv_file(const std::filesystem::path& path, const CsvTable& table) {
  write_file_atomically(path, [&](std::ostream& out) { write_csv(out, table); });
}

}  // namespace windplan
