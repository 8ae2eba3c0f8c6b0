#include "cli/pairs_reader.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "geometry/base/errors.h"

namespace windplan::cli {

bool parse_double(const std::string& s, double* out) {
  const char* b = s.c_str();
  char* end = nullptr;
  *out = std::strtod(b, &end);
  return end != b && end == b + s.size();  // a NUL inside `s` is not its end
}

SurfacePoint parse_point(const Mesh& mesh, const ClosestPointQuery& query, double tolerance,
                         const std::string& option, const std::string& text) {
  if (text.find(',') == std::string::npos) {
    char* end = nullptr;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (end == text.c_str() || end != text.c_str() + text.size()) {
      throw UsageError(option + " expects a vertex index or x,y,z, got '" + text + "'");
    }
    if (v < 0 || v >= mesh.num_vertices()) {
      throw InputError(option + " " + text + ": vertex index out of range (the mesh has " +
                       std::to_string(mesh.num_vertices()) + " vertices, 0 to " +
                       std::to_string(mesh.num_vertices() - 1) + ")");
    }
    if (mesh.vertex_halfedge(static_cast<int>(v)) < 0) {
      throw InputError(option + " " + text + ": vertex " + text +
                       " is not used by any face of the mesh");
    }
    return SurfacePoint::at_vertex(static_cast<int>(v));
  }
  Vec3 p;
  std::istringstream in(text);
  std::string part;
  int n = 0;
  while (std::getline(in, part, ',')) {
    double d = 0.0;
    if (n >= 3 || !parse_double(part, &d) || !std::isfinite(d)) {
      throw UsageError(option + " expects a vertex index or x,y,z, got '" + text + "'");
    }
    p[n++] = d;
  }
  if (n != 3) throw UsageError(option + " expects a vertex index or x,y,z, got '" + text + "'");
  const ClosestPointQuery::Hit hit = query.closest(p);
  if (!(hit.distance <= tolerance)) {
    std::ostringstream s;
    s << option << " " << text << ": the point is " << hit.distance
      << " mm from the mesh (more than the snap tolerance " << tolerance << " mm)";
    throw InputError(s.str());
  }
  return hit.point;
}

std::vector<BatchLine> batch_lines_of(const std::string& text, const std::string& file) {
  std::istringstream in(text);
  std::vector<BatchLine> lines;
  std::string line;
  int no = 0;
  while (std::getline(in, line)) {
    ++no;
    // A NUL or another control character inside a token was cut by the number parser and
    // copied whole into the CSV (issue 28): a batch file is plain text.
    for (const char c : line) {
      const unsigned char u = static_cast<unsigned char>(c);
      if ((u < 0x20 && c != '\t' && c != '\r') || u == 0x7f) {
        char code[8];
        std::snprintf(code, sizeof code, "%02X", u);
        throw InputError(file + ":" + std::to_string(no) + ": a control character (" +
                         (u == 0 ? std::string("NUL") : "byte 0x" + std::string(code)) +
                         ") in the line; a batch file is plain text");
      }
    }
    std::string clean = line;
    for (char& c : clean)
      if (c == '\t' || c == '\r' || c == ';') c = ' ';
    std::istringstream ls(clean);
    BatchLine bl{no, line, {}};
    for (std::string tok; ls >> tok;) bl.tokens.push_back(tok);
    if (bl.tokens.empty() || bl.tokens[0][0] == '#') continue;
    lines.push_back(std::move(bl));
  }
  return lines;
}

std::vector<BatchPair> read_pairs_of(const std::string& text, const std::string& file,
                                     const Mesh& mesh, const ClosestPointQuery& query,
                                     double tolerance) {
  std::vector<BatchPair> pairs;
  for (const BatchLine& bl : batch_lines_of(text, file)) {
    const int no = bl.number;
    const std::string& line = bl.text;
    const std::vector<std::string>& toks = bl.tokens;
    const std::string at = file + ":" + std::to_string(no) + ": ";
    if (toks.size() != 2) {
      throw InputError(at + "expected two points 'FROM TO' (a vertex index or x,y,z each), got '" +
                       line + "'");
    }
    BatchPair p;
    p.line = no;
    p.from = toks[0];
    p.to = toks[1];
    try {
      p.a = parse_point(mesh, query, tolerance, "from", toks[0]);
      p.b = parse_point(mesh, query, tolerance, "to", toks[1]);
    } catch (const Error& e) {
      throw InputError(at + e.what());
    }
    pairs.push_back(std::move(p));
  }
  if (pairs.empty()) throw InputError(file + ": no pairs (one 'FROM TO' per line)");
  return pairs;
}

}  // namespace windplan::cli
