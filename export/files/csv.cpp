#include "export/files/csv.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <vector>

#include "geometry/base/atomic_file.h"
#include "geometry/base/errors.h"
#include "geometry/base/parallel.h"

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
  std::string head;
  for (std::size_t i = 0; i < table.header.size(); ++i) {
    head += i ? "," : "";
    head += table.header[i];
  }
  head += "\n";
  out.write(head.data(), static_cast<std::streamsize>(head.size()));
  for (const auto& row : table.rows) {
    if (row.size() != table.header.size()) {
      throw InvariantError("CSV row has " + std::to_string(row.size()) + " values for " +
                           std::to_string(table.header.size()) + " columns");
    }
  }
  // The rows in chunks of kChunk, formatted in parallel a batch of kBatch chunks at a time (a
  // few MB of text: a job's fibre path has hundreds of thousands of rows) and written in order.
  constexpr std::size_t kChunk = 4096, kBatch = 16;
  const std::size_t n = table.rows.size();
  std::vector<std::string> text(kBatch);
  for (std::size_t batch = 0; batch < n; batch += kChunk * kBatch) {
    const int chunks = static_cast<int>(std::min(kBatch, (n - batch + kChunk - 1) / kChunk));
    parallel_for_index(chunks, [&](int c) {
      std::string& buf = text[c];
      buf.clear();
      const std::size_t begin = batch + c * kChunk, end = std::min(n, begin + kChunk);
      for (std::size_t r = begin; r < end; ++r) {
        const std::vector<double>& row = table.rows[r];
        for (std::size_t i = 0; i < row.size(); ++i) {
          if (i) buf += ',';
          append_number(&buf, row[i], table.digits);
        }
        buf += '\n';
      }
    });
    for (int c = 0; c < chunks; ++c) {
      out.write(text[c].data(), static_cast<std::streamsize>(text[c].size()));
    }
  }
}

void write_csv_file(const std::filesystem::path& path, const CsvTable& table) {
  write_file_atomically(path, [&](std::ostream& out) { write_csv(out, table); });
}

}  // namespace windplan
