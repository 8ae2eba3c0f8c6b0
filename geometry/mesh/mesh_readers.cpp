// The mesh readers (geometry/mesh/mesh_readers.h): a pointer tokenizer over the whole file, and
// one reader per format.
#include "geometry/mesh/mesh_readers.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <unordered_map>

namespace windplan {
namespace mesh_readers {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

const char* skip_spaces(const char* p, const char* end) {
  while (p < end && is_space(*p)) ++p;
  return p;
}

const char* skip_token(const char* p, const char* end) {
  while (p < end && !is_space(*p) && *p != '\n') ++p;
  return p;
}

// Parses a double at p (leading '+' allowed, which from_chars rejects). Returns the end of the
// number or nullptr when there is none.
const char* parse_double(const char* p, const char* end, double* out) {
  if (p < end && *p == '+') ++p;
  const auto r = std::from_chars(p, end, *out, std::chars_format::general);
  if (r.ec == std::errc::result_out_of_range) {
    // Overflow or underflow: let strtod decide (it gives +-inf or a denormal/0).
    std::string tok(p, skip_token(p, end));
    *out = std::strtod(tok.c_str(), nullptr);
    return p + tok.size();
  }
  if (r.ec != std::errc()) return nullptr;
  return r.ptr;
}

const char* parse_long(const char* p, const char* end, long long* out) {
  if (p < end && *p == '+') ++p;
  const auto r = std::from_chars(p, end, *out);
  if (r.ec != std::errc()) return nullptr;
  return r.ptr;
}

std::string token_at(const char* p, const char* end) {
  const char* e = skip_token(p, end);
  std::string t(p, std::min<std::size_t>(e - p, 40));
  return t.empty() ? std::string("end of line") : "'" + t + "'";
}

// A token stream over a text buffer that counts lines and treats '#' as a comment to the end of
// the line (OFF, ascii STL, ascii PLY bodies).
class Tokens {
 public:
  Tokens(const char* p, const char* end, int line, bool comments)
      : p_(p), end_(end), line_(line), comments_(comments) {}

  /// Moves to the start of the next token; false at the end of the data.
  bool next() {
    for (;;) {
      while (p_ < end_ && (is_space(*p_) || *p_ == '\n')) {
        if (*p_ == '\n') ++line_;
        ++p_;
      }
      if (p_ < end_ && comments_ && *p_ == '#') {
        while (p_ < end_ && *p_ != '\n') ++p_;
        continue;
      }
      return p_ < end_;
    }
  }
  /// Skips the rest of the current line (and its newline).
  void skip_line() {
    while (p_ < end_ && *p_ != '\n') ++p_;
    if (p_ < end_) {
      ++p_;
      ++line_;
    }
  }
  /// True when only spaces/comments remain on the current line.
  bool at_line_end() {
    while (p_ < end_ && is_space(*p_)) ++p_;
    return p_ >= end_ || *p_ == '\n' || (comments_ && *p_ == '#');
  }
  std::string word() {
    const char* e = skip_token(p_, end_);
    std::string w(p_, e);
    p_ = e;
    return w;
  }
  bool number(double* out) {
    const char* e = parse_double(p_, end_, out);
    if (!e || (e < end_ && !is_space(*e) && *e != '\n' && !(comments_ && *e == '#'))) return false;
    p_ = e;
    return true;
  }
  bool integer(long long* out) {
    const char* e = parse_long(p_, end_, out);
    if (!e || (e < end_ && !is_space(*e) && *e != '\n' && !(comments_ && *e == '#'))) return false;
    p_ = e;
    return true;
  }
  int line() const { return line_; }
  const char* pos() const { return p_; }
  const char* end() const { return end_; }

 private:
  const char* p_;
  const char* end_;
  int line_;
  bool comments_;
};

void check_finite(const std::filesystem::path& path, const Vec3& p, std::size_t vertex, int line) {
  if (std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z())) return;
  std::ostringstream s;
  s << "vertex " << vertex << " has a NaN or infinite coordinate (" << p.x() << ", " << p.y()
    << ", " << p.z() << ")";
  if (line > 0) fail_line(path, line, s.str());
  fail(path, s.str());
}

void fan_split(const std::vector<int>& poly, std::vector<Tri>* tris) {
  for (std::size_t i = 1; i + 1 < poly.size(); ++i)
    tris->push_back({poly[0], poly[i], poly[i + 1]});
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// OBJ

TriangleSoup read_obj(const std::filesystem::path& path, const std::string& data) {
  TriangleSoup soup;
  const char* p = data.data();
  const char* const end = p + data.size();
  soup.points.reserve(data.size() / 60);
  soup.triangles.reserve(data.size() / 30);
  std::vector<int> poly;
  int line = 0;
  while (p < end) {
    ++line;
    const char* eol = static_cast<const char*>(std::memchr(p, '\n', end - p));
    if (!eol) eol = end;
    const char* q = skip_spaces(p, eol);
    if (q + 1 < eol && is_space(q[1]) && q[0] == 'v') {
      q += 2;
      double c[3];
      for (int k = 0; k < 3; ++k) {
        q = skip_spaces(q, eol);
        const char* e = parse_double(q, eol, &c[k]);
        if (!e || (e < eol && !is_space(*e))) {
          fail_line(path, line, "malformed vertex coordinate " + token_at(q, eol));
        }
        q = e;
      }
      // Then x y z [w] or x y z r g b (vertex colours): 0, 1 or 3 more numbers. A line of more
      // (1e7 numbers were read as one vertex, every index after it shifted) is refused.
      int extra = 0;
      for (;;) {
        q = skip_spaces(q, eol);
        if (q >= eol || *q == '#' || *q == '\r') break;
        double unused = 0.0;
        const char* e = parse_double(q, eol, &unused);
        if (!e || (e < eol && !is_space(*e))) {
          fail_line(path, line, "malformed vertex coordinate " + token_at(q, eol));
        }
        q = e;
        if (++extra > 3) break;
      }
      if (extra == 2 || extra > 3) {
        fail_line(path, line,
                  std::string("a 'v' line with ") + (extra > 3 ? "more than 6" : "5") +
                      " numbers; a vertex is 'v x y z', 'v x y z w' or 'v x y z r g b' (one "
                      "vertex per line)");
      }
      soup.points.emplace_back(c[0], c[1], c[2]);
      check_finite(path, soup.points.back(), soup.points.size() - 1, line);
    } else if (q + 1 < eol && is_space(q[1]) && q[0] == 'f') {
      q += 2;
      poly.clear();
      const long long nv = static_cast<long long>(soup.points.size());
      for (;;) {
        q = skip_spaces(q, eol);
        if (q >= eol || *q == '#') break;
        long long idx = 0;
        const char* e = parse_long(q, eol, &idx);
        if (!e || (e < eol && !is_space(*e) && *e != '/')) {
          fail_line(path, line, "malformed face index " + token_at(q, eol));
        }
        // 1-based, or negative = relative to the vertices read so far.
        const long long i0 = idx > 0 ? idx - 1 : nv + idx;
        if (idx == 0 || i0 < 0 || i0 >= nv) {
          fail_line(path, line,
                    "face index " + std::to_string(idx) + " is out of range (" +
                        std::to_string(nv) + " vertices defined so far)");
        }
        poly.push_back(static_cast<int>(i0));
        q = skip_token(e, eol);  // the /vt/vn part
      }
      if (poly.size() < 3) {
        fail_line(path, line, "face with " + std::to_string(poly.size()) + " vertices (needs 3+)");
      }
      fan_split(poly, &soup.triangles);
    }
    // Everything else (vt, vn, o, g, s, usemtl, mtllib, l, comments) is ignored.
    p = eol + 1;
  }
  return soup;
}

// ---------------------------------------------------------------------------------------------
// OFF

TriangleSoup read_off(const std::filesystem::path& path, const std::string& data) {
  Tokens t(data.data(), data.data() + data.size(), 1, true);
  if (!t.next()) fail(path, "empty file (no OFF header)");
  const std::string head = t.word();
  // OFF, COFF, NOFF, STOFF...: coordinates come first on every vertex line either way.
  if (head.size() < 3 || head.compare(head.size() - 3, 3, "OFF") != 0) {
    fail_line(path, t.line(), "not an OFF file: first word is '" + head + "', expected 'OFF'");
  }
  // "OFF nv nf ne" on one line or over several; the edge count may be missing.
  long long counts[3] = {0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    if (k == 2 && t.at_line_end()) break;
    if (!t.next() || !t.integer(&counts[k]) || counts[k] < 0) {
      fail_line(path, t.line(),
                "expected the vertex, face and edge counts after 'OFF', got " +
                    token_at(t.pos(), t.end()));
    }
  }
  const long long nv = counts[0], nf = counts[1];
  if (nv > std::numeric_limits<int>::max() || nf > std::numeric_limits<int>::max()) {
    fail(path,
         "vertex or face count too large (" + std::to_string(nv) + ", " + std::to_string(nf) + ")");
  }
  TriangleSoup soup;
  const long long cap = static_cast<long long>(data.size());  // a corrupt header may claim more
  soup.points.reserve(std::min(nv, cap));
  t.skip_line();
  for (long long i = 0; i < nv; ++i) {
    double c[3];
    for (int k = 0; k < 3; ++k) {
      if (!t.next()) {
        fail(path,
             "truncated: expected " + std::to_string(nv) + " vertices, found " + std::to_string(i));
      }
      if (!t.number(&c[k])) {
        fail_line(path, t.line(), "malformed coordinate " + token_at(t.pos(), t.end()));
      }
    }
    soup.points.emplace_back(c[0], c[1], c[2]);
    check_finite(path, soup.points.back(), i, t.line());
    t.skip_line();  // colours or extra columns
  }
  std::vector<int> poly;
  soup.triangles.reserve(std::min(2 * nf, cap));
  for (long long f = 0; f < nf; ++f) {
    long long n = 0;
    if (!t.next()) {
      fail(path,
           "truncated: expected " + std::to_string(nf) + " faces, found " + std::to_string(f));
    }
    if (!t.integer(&n) || n < 3) {
      fail_line(path, t.line(), "malformed face vertex count " + token_at(t.pos(), t.end()));
    }
    poly.clear();
    for (long long k = 0; k < n; ++k) {
      long long idx = 0;
      if (!t.next() || !t.integer(&idx)) {
        fail_line(path, t.line(), "malformed face index " + token_at(t.pos(), t.end()));
      }
      if (idx < 0 || idx >= nv) {
        fail_line(path, t.line(),
                  "face " + std::to_string(f) + " index " + std::to_string(idx) +
                      " is out of range [0, " + std::to_string(nv) + ")");
      }
      poly.push_back(static_cast<int>(idx));
    }
    fan_split(poly, &soup.triangles);
    t.skip_line();
  }
  return soup;
}

// ---------------------------------------------------------------------------------------------
// PLY

namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64, None };

PlyType ply_type(const std::string& s) {
  if (s == "char" || s == "int8") return PlyType::Int8;
  if (s == "uchar" || s == "uint8") return PlyType::UInt8;
  if (s == "short" || s == "int16") return PlyType::Int16;
  if (s == "ushort" || s == "uint16") return PlyType::UInt16;
  if (s == "int" || s == "int32") return PlyType::Int32;
  if (s == "uint" || s == "uint32") return PlyType::UInt32;
  if (s == "float" || s == "float32") return PlyType::Float32;
  if (s == "double" || s == "float64") return PlyType::Float64;
  return PlyType::None;
}

int ply_size(PlyType t) {
  switch (t) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
    case PlyType::None:
      return 0;
  }
  return 0;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::None;        // scalar type, or list item type
  PlyType count_type = PlyType::None;  // list count type; None for a scalar
};

struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> props;
};

// Reads the values of a PLY body, binary (either endianness) or ascii, one at a time.
class PlyBody {
 public:
  PlyBody(const std::filesystem::path& path, const char* begin, const char* end, bool ascii,
          bool big_endian, int line, std::size_t header_bytes)
      : path_(path),
        begin_(begin),
        p_(begin),
        end_(end),
        ascii_(ascii),
        swap_(big_endian == host_is_little_endian()),
        tokens_(begin, end, line, false),
        header_bytes_(header_bytes) {}

  /// \param what the element being read, for messages ("vertex 12 of 100")
  double read(PlyType t, const std::string& what) {
    if (ascii_) {
      double d;
      if (!tokens_.next()) {
        fail(path_, "truncated ascii PLY: the data ends in " + what);
      }
      if (!tokens_.number(&d)) {
        fail_line(path_, tokens_.line(),
                  "malformed number " + token_at(tokens_.pos(), tokens_.end()) + " in " + what);
      }
      return d;
    }
    const int n = ply_size(t);
    if (end_ - p_ < n) {
      fail(path_, "truncated binary PLY: needs at least " +
                      std::to_string(header_bytes_ + (p_ - begin_) + n) +
                      " bytes (the data ends in " + what + "), the file has " +
                      std::to_string(header_bytes_ + (end_ - begin_)) + " bytes");
    }
    unsigned char b[8];
    std::memcpy(b, p_, n);
    p_ += n;
    if (swap_) std::reverse(b, b + n);
    switch (t) {
      case PlyType::Int8: {
        std::int8_t v;
        std::memcpy(&v, b, 1);
        return v;
      }
      case PlyType::UInt8:
        return b[0];
      case PlyType::Int16: {
        std::int16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case PlyType::UInt16: {
        std::uint16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case PlyType::Int32: {
        std::int32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case PlyType::UInt32: {
        std::uint32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case PlyType::Float32: {
        float v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case PlyType::Float64: {
        double v;
        std::memcpy(&v, b, 8);
        return v;
      }
      case PlyType::None:
        break;
    }
    return 0.0;
  }
  /// Fast skip of n fixed-size binary bytes (a run of scalar properties nobody needs).
  void skip_bytes(std::size_t n, const std::string& what) {
    if (static_cast<std::size_t>(end_ - p_) < n) {
      fail(path_, "truncated binary PLY: needs at least " +
                      std::to_string(header_bytes_ + (p_ - begin_) + n) +
                      " bytes (the data ends in " + what + "), the file has " +
                      std::to_string(header_bytes_ + (end_ - begin_)) + " bytes");
    }
    p_ += n;
  }
  bool ascii() const { return ascii_; }
  int line() const { return ascii_ ? tokens_.line() : 0; }

 private:
  const std::filesystem::path& path_;
  const char* begin_;
  const char* p_;
  const char* end_;
  bool ascii_;
  bool swap_;
  Tokens tokens_;
  std::size_t header_bytes_;
};

}  // namespace

TriangleSoup read_ply(const std::filesystem::path& path, const std::string& data) {
  const char* const begin = data.data();
  const char* const end = begin + data.size();
  const char* p = begin;
  int line = 0;
  auto next_line = [&](std::string* out) -> bool {
    if (p >= end) return false;
    const char* eol = static_cast<const char*>(std::memchr(p, '\n', end - p));
    if (!eol) eol = end;
    const char* e = eol;
    if (e > p && e[-1] == '\r') --e;
    out->assign(p, e);
    p = eol < end ? eol + 1 : end;
    ++line;
    return true;
  };
  std::string l;
  if (!next_line(&l) || l != "ply") fail(path, "not a PLY file (the first line is not 'ply')");
  bool ascii = false, big = false, have_format = false;
  std::vector<PlyElement> elements;
  bool ended = false;
  while (next_line(&l)) {
    std::istringstream s(l);
    std::string kw;
    s >> kw;
    if (kw.empty() || kw == "comment" || kw == "obj_info") continue;
    if (kw == "end_header") {
      ended = true;
      break;
    }
    if (kw == "format") {
      std::string f;
      s >> f;
      if (f == "ascii")
        ascii = true;
      else if (f == "binary_little_endian")
        big = false;
      else if (f == "binary_big_endian")
        big = true;
      else
        fail_line(path, line, "unknown PLY format '" + f + "'");
      have_format = true;
    } else if (kw == "element") {
      PlyElement e;
      if (!(s >> e.name >> e.count) || e.count < 0) {
        fail_line(path, line, "malformed element line '" + l + "'");
      }
      if (e.count > std::numeric_limits<int>::max()) {
        fail_line(path, line,
                  "element '" + e.name + "' count " + std::to_string(e.count) + " is too large");
      }
      elements.push_back(e);
    } else if (kw == "property") {
      if (elements.empty()) fail_line(path, line, "property before any element");
      PlyProperty prop;
      std::string t;
      s >> t;
      if (t == "list") {
        std::string ct, it;
        s >> ct >> it >> prop.name;
        prop.count_type = ply_type(ct);
        prop.type = ply_type(it);
        if (prop.count_type == PlyType::None || prop.type == PlyType::None) {
          fail_line(path, line, "unknown list type in '" + l + "'");
        }
      } else {
        prop.type = ply_type(t);
        s >> prop.name;
        if (prop.type == PlyType::None) fail_line(path, line, "unknown property type '" + t + "'");
      }
      if (prop.name.empty()) fail_line(path, line, "property without a name");
      elements.back().props.push_back(prop);
    } else {
      fail_line(path, line, "unexpected header line '" + l + "'");
    }
  }
  if (!ended) fail(path, "truncated PLY header: no 'end_header' line");
  if (!have_format) fail(path, "PLY header has no 'format' line");

  PlyBody body(path, p, end, ascii, big, line + 1, static_cast<std::size_t>(p - begin));
  TriangleSoup soup;
  std::vector<int> poly;
  for (const PlyElement& el : elements) {
    const bool is_vertex = el.name == "vertex";
    const bool is_face = el.name == "face";
    int ix = -1, iy = -1, iz = -1, iface = -1;
    for (int k = 0; k < static_cast<int>(el.props.size()); ++k) {
      const PlyProperty& pr = el.props[k];
      if (is_vertex && pr.count_type == PlyType::None) {
        if (pr.name == "x") ix = k;
        if (pr.name == "y") iy = k;
        if (pr.name == "z") iz = k;
      }
      if (is_face && pr.count_type != PlyType::None &&
          (pr.name == "vertex_indices" || pr.name == "vertex_index")) {
        iface = k;
      }
    }
    if (is_vertex && (ix < 0 || iy < 0 || iz < 0)) {
      fail(path, "PLY vertex element has no x, y, z properties");
    }
    if (is_face && iface < 0) fail(path, "PLY face element has no vertex_indices list");
    // A binary element made only of scalars nobody reads is skipped in one step.
    bool all_scalar = true;
    std::size_t scalar_bytes = 0;
    for (const auto& pr : el.props) {
      all_scalar = all_scalar && pr.count_type == PlyType::None;
      scalar_bytes += ply_size(pr.type);
    }
    if (!is_vertex && !is_face && all_scalar && !ascii) {
      body.skip_bytes(scalar_bytes * el.count, "element '" + el.name + "'");
      continue;
    }
    // Reserve no more than the data can hold: a corrupt header may claim billions.
    const long long cap = static_cast<long long>(data.size());
    if (is_vertex) soup.points.reserve(std::min(el.count, cap));
    if (is_face) soup.triangles.reserve(std::min(2 * el.count, cap));
    for (long long i = 0; i < el.count; ++i) {
      auto what = [&]() {
        return el.name + " " + std::to_string(i) + " of " + std::to_string(el.count);
      };
      Vec3 pt(0, 0, 0);
      const int line_before = body.line();
      for (int k = 0; k < static_cast<int>(el.props.size()); ++k) {
        const PlyProperty& pr = el.props[k];
        if (pr.count_type == PlyType::None) {
          const double v = body.read(pr.type, what());
          if (k == ix) pt.x() = v;
          if (k == iy) pt.y() = v;
          if (k == iz) pt.z() = v;
          continue;
        }
        const double cnt = body.read(pr.count_type, what());
        if (!(cnt >= 0) || cnt != std::floor(cnt) || cnt > 1e6) {
          fail(path, "invalid list length " + std::to_string(cnt) + " in " + what());
        }
        const long long n = static_cast<long long>(cnt);
        if (k == iface) poly.clear();
        for (long long j = 0; j < n; ++j) {
          const double v = body.read(pr.type, what());
          if (k == iface) {
            if (!(v >= 0) || v != std::floor(v) || v > std::numeric_limits<int>::max()) {
              fail(path, "invalid vertex index " + std::to_string(v) + " in " + what());
            }
            poly.push_back(static_cast<int>(v));
          }
        }
        if (k == iface) {
          if (poly.size() < 3) {
            fail(path, what() + " has " + std::to_string(poly.size()) + " vertices (needs 3+)");
          }
          for (int v : poly) {
            if (v >= static_cast<long long>(soup.points.size())) {
              fail(path, what() + " has vertex index " + std::to_string(v) + " out of range [0, " +
                             std::to_string(soup.points.size()) + ")");
            }
          }
          fan_split(poly, &soup.triangles);
        }
      }
      if (is_vertex) {
        soup.points.push_back(pt);
        check_finite(path, pt, soup.points.size() - 1, line_before);
      }
    }
  }
  return soup;
}

// ---------------------------------------------------------------------------------------------
// STL

namespace {

TriangleSoup read_stl_ascii(const std::filesystem::path& path, const std::string& data) {
  Tokens t(data.data(), data.data() + data.size(), 1, false);
  TriangleSoup soup;
  while (t.next()) {
    const int line = t.line();
    const std::string w = t.word();
    if (w != "vertex") continue;
    double c[3];
    for (int k = 0; k < 3; ++k) {
      if (!t.next() || !t.number(&c[k])) {
        fail_line(path, t.line(), "malformed vertex coordinate " + token_at(t.pos(), t.end()));
      }
    }
    soup.points.emplace_back(c[0], c[1], c[2]);
    check_finite(path, soup.points.back(), soup.points.size() - 1, line);
  }
  if (soup.points.size() % 3 != 0) {
    fail(path, "ascii STL has " + std::to_string(soup.points.size()) +
                   " 'vertex' lines, not a multiple of 3 (truncated?)");
  }
  for (int i = 0; i + 2 < static_cast<int>(soup.points.size()); i += 3) {
    soup.triangles.push_back({i, i + 1, i + 2});
  }
  return soup;
}

TriangleSoup read_stl_binary(const std::filesystem::path& path, const std::string& data,
                             std::uint32_t n) {
  TriangleSoup soup;
  soup.points.resize(3 * static_cast<std::size_t>(n));
  soup.triangles.resize(n);
  const bool swap = !host_is_little_endian();
  for (std::uint32_t i = 0; i < n; ++i) {
    const char* rec = data.data() + 84 + 50 * static_cast<std::size_t>(i);
    for (int k = 0; k < 3; ++k) {
      float c[3];
      for (int j = 0; j < 3; ++j) {
        unsigned char b[4];
        std::memcpy(b, rec + 12 + 12 * k + 4 * j, 4);
        if (swap) std::reverse(b, b + 4);
        std::memcpy(&c[j], b, 4);
      }
      const std::size_t v = 3 * static_cast<std::size_t>(i) + k;
      soup.points[v] = Vec3(c[0], c[1], c[2]);
      if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2])) {
        fail(path, "triangle " + std::to_string(i) + " corner " + std::to_string(k) +
                       " has a NaN or infinite coordinate");
      }
    }
    const int b = static_cast<int>(3 * i);
    soup.triangles[i] = {b, b + 1, b + 2};
  }
  return soup;
}

}  // namespace

TriangleSoup read_stl(const std::filesystem::path& path, const std::string& data,
                      const MeshReadOptions& options) {
  // Binary iff the size matches 84 + 50 n exactly: a binary file may well start with "solid"
  // (many exporters write that into the 80-byte header), so the first word proves nothing.
  std::uint32_t n = 0;
  bool binary = false;
  if (data.size() >= 84) {
    unsigned char b[4];
    std::memcpy(b, data.data() + 80, 4);
    n = b[0] | (b[1] << 8) | (b[2] << 16) | (static_cast<std::uint32_t>(b[3]) << 24);
    binary = data.size() == 84 + 50 * static_cast<std::uint64_t>(n);
  }
  const char* q = skip_spaces(data.data(), data.data() + data.size());
  while (q < data.data() + data.size() && *q == '\n')
    q = skip_spaces(q + 1, data.data() + data.size());
  const bool starts_solid = static_cast<std::size_t>(data.data() + data.size() - q) >= 5 &&
                            std::strncmp(q, "solid", 5) == 0;
  const bool has_facet =
      data.find("facet", 0) != std::string::npos && data.find("vertex", 0) != std::string::npos;
  TriangleSoup soup;
  if (binary) {
    soup = read_stl_binary(path, data, n);
  } else if (starts_solid && has_facet) {
    soup = read_stl_ascii(path, data);
  } else if (data.size() < 84) {
    fail(path, "truncated STL: " + std::to_string(data.size()) +
                   " bytes is neither ascii STL nor a binary STL (needs at least 84 bytes)");
  } else {
    fail(path, "truncated or corrupt binary STL: the header announces " + std::to_string(n) +
                   " triangles, so the file should have 84 + 50 * " + std::to_string(n) + " = " +
                   std::to_string(84 + 50 * static_cast<std::uint64_t>(n)) + " bytes, it has " +
                   std::to_string(data.size()));
  }
  if (soup.triangles.empty()) fail(path, "STL contains no triangles");
  BoundingBox box;
  box.min = box.max = soup.points[0];
  for (const Vec3& pt : soup.points) {
    box.min = box.min.cwiseMin(pt);
    box.max = box.max.cwiseMax(pt);
  }
  return weld_vertices(soup, options.weld_tolerance * box.diagonal_length());
}

}  // namespace mesh_readers
}  // namespace windplan
