#pragma once
// Deterministic CSV tables: a header line with units, then rows of numbers printed with a fixed
// precision, so that two runs of the same job give byte-identical files. Written atomically.
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace windplan {

struct CsvTable {
  /// Column names, units in brackets where they apply: "x [mm]".
  std::vector<std::string> header;
  /// Rows of values; each row has header.size() entries.
  std::vector<std::vector<double>> rows;
  /// Significant digits for doubles (integers are printed as integers).
  int digits = 10;
};

/// Writes the table as CSV text.
void write_csv(std::ostream& out, const CsvTable& table);
/// Writes the table to a file atomically. \throw IoError
void write_csv_file(const std::filesystem::path& path, const CsvTable& table);
/// Formats one number the way write_csv does.
std::string format_csv_number(double v, int digits);

}  // namespace windplan
