#include "export/files/cutlines_csv.h"

#include <string>

#include "export/files/csv.h"
#include "geometry/base/atomic_file.h"

namespace windplan {

namespace {

// RFC 4180 quoting, only where needed, so plain names stay plain.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

void write_cutlines_csv(std::ostream& out, const std::vector<CutLine>& cutlines, int digits) {
  out << "name,index,x [mm],y [mm],z [mm]\n";
  for (const CutLine& c : cutlines) {
    const std::string name = csv_field(c.name);
    for (std::size_t i = 0; i < c.points.size(); ++i) {
      const Vec3& p = c.points[i];
      out << name << ',' << i << ',' << format_csv_number(p.x(), digits) << ','
          << format_csv_number(p.y(), digits) << ',' << format_csv_number(p.z(), digits) << '\n';
    }
  }
}

void write_cutlines_csv(const std::filesystem::path& path, const std::vector<CutLine>& cutlines,
                        int digits) {
  write_file_atomically(path,
                        [&](std::ostream& out) { write_cutlines_csv(out, cutlines, digits); });
}

}  // namespace windplan
