#include "export/files/csv.h"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "geometry/base/atomic_file.h"
#include "geometry/base/errors.h"

namespace windplan {

namespace {

// Appends v the way format_csv_number prints it. std::to_chars with a precision prints exactly
// what printf("%.*g") prints, several times faster (the CSV files hold millions of numbers).
void append_number(std::string* out, double v, int digits) {
  char buf[64];
  if (!std::isfinite(v)) {
    *out += "nan";
    return;
  }
  if (v == std::floor(v) && std::fabs(v) < 1e15) {
    const long long i = static_cast<long long>(v);
    const auto r = std::to_chars(buf, buf + sizeof buf, i);
    out->append(buf, r.ptr);
    return;
  }
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, digits);
  out->append(buf, r.ptr);
}

}  // namespace

std::string format_csv_number(double v, int digits) {
  std::string s;
  append_number(&s, v, digits);
  return s;
}

void write_csv(std::ostream& out, const CsvTable& table) {
  std::string buf;
  for (std::size_t i = 0; i < table.header.size(); ++i) {
    buf += i ? "," : "";
    buf += table.header[i];
  }
  buf += "\n";
  for (const auto& row : table.rows) {
    if (row.size() != table.header.size()) {
      throw InvariantError("CSV row has " + std::to_string(row.size()) + " values for " +
                           std::to_string(table.header.size()) + " columns");
    }
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (i) buf += ',';
      append_number(&buf, row[i], table.digits);
    }
    buf += '\n';
    if (buf.size() > (1 << 20)) {
      out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
      buf.clear();
    }
  }
  out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
}

void write_csv_file(const std::filesystem::path& path, const CsvTable& table) {
  write_file_atomically(path, [&](std::ostream& out) { write_csv(out, table); });
}

}  // namespace windplan
