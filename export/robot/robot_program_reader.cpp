#include "export/robot/robot_program_reader.h"

#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"
#include "geometry/base/input_file.h"

namespace windplan {

namespace {

constexpr double kRad = M_PI / 180.0;

struct Text {
  std::string name;  // file name for messages
  std::vector<std::string> lines;
};

/// Files from disk, or from memory when `memory` is set (names without folder).
struct Source {
  const std::map<std::string, std::string>* memory = nullptr;
  bool exists(const std::filesystem::path& p) const {
    return memory ? memory->count(p.filename().string()) > 0 : std::filesystem::exists(p);
  }
  Text load(const std::filesystem::path& file) const;
};

Text Source::load(const std::filesystem::path& file) const {
  std::stringstream in;
  if (memory) {
    const auto it = memory->find(file.filename().string());
    if (it == memory->end()) throw IoError(file.string() + ": no such robot program file");
    in.str(it->second);
  } else {
    // A regular file of bounded size, read once (geometry/base/input_file.h).
    in.str(read_input_file(file, kProgramFileCap, "a robot program file"));
  }
  Text t;
  t.name = file.filename().string();
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    t.lines.push_back(line);
  }
  return t;
}

std::string trim(const std::string& s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

/// Removes a comment starting with `c` outside double quotes.
std::string code_of(const std::string& line, char c) {
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '"') quoted = !quoted;
    if (line[i] == c && !quoted) return trim(line.substr(0, i));
  }
  return trim(line);
}

[[noreturn]] void bad(const std::string& file, int line, const std::string& msg) {
  throw InputError(file + ":" + std::to_string(line) + ": " + msg);
}

double number(const std::string& s, const std::string& file, int line, const std::string& what) {
  const std::string t = trim(s);
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(t, &used);
  } catch (...) {
    used = 0;
  }
  if (t.empty() || used != t.size() || !std::isfinite(v)) {
    bad(file, line, what + ": '" + t + "' is not a number");
  }
  return v;
}

constexpr double kMaxPosition = 1e5;  // mm: a target beyond 100 m is no cell's (gcode_reader too)
constexpr double kMaxAngle = 360.0;   // deg: KUKA's A, B, C
constexpr double kMaxE1 = 1e9;        // deg: the positioner's E1 (many turns, but a number)

/// A position component: finite (number()) and within 100 m.
double position(double v, const std::string& file, int line, const std::string& what) {
  if (std::fabs(v) > kMaxPosition) {
    bad(file, line,
        what + " = " + format_shortest(v) +
            " mm is beyond 100 m: no robot cell reaches so far (a value in microns, or a typo?)");
  }
  return v;
}

/// A configuration status (KUKA's S, ABB's cfx): a whole number 0 to 7.
int status(double v, const std::string& file, int line, const std::string& what) {
  if (!(v == std::floor(v) && v >= 0.0 && v <= 7.0)) {
    bad(file, line, what + " = " + format_shortest(v) + ": a status is a whole number 0 to 7");
  }
  return static_cast<int>(v);
}

Eigen::Matrix3d kuka_abc(double a, double b, double c) {
  return (Eigen::AngleAxisd(a * kRad, Vec3::UnitZ()) * Eigen::AngleAxisd(b * kRad, Vec3::UnitY()) *
          Eigen::AngleAxisd(c * kRad, Vec3::UnitX()))
      .toRotationMatrix();
}

// ---- KRL ----

using Aggregate = std::map<std::string, double>;

/// {X 1.0,Y 2.0,...} -> components by upper-case name.
Aggregate krl_aggregate(const std::string& text, const std::string& file, int line) {
  const std::string t = trim(text);
  if (t.size() < 2 || t.front() != '{' || t.back() != '}') {
    bad(file, line, "expected a KRL aggregate {X ..., Y ...}, got '" + t + "'");
  }
  Aggregate a;
  std::stringstream ss(t.substr(1, t.size() - 2));
  std::string item;
  while (std::getline(ss, item, ',')) {
    item = trim(item);
    if (item.empty()) continue;
    const std::size_t sp = item.find_first_of(" \t");
    if (sp == std::string::npos) bad(file, line, "aggregate component '" + item + "' has no value");
    std::string key = upper(trim(item.substr(0, sp)));
    if (key.find(':') != std::string::npos) {  // a type prefix such as "E6POS: X"
      key = upper(trim(key.substr(key.find(':') + 1)));
    }
    a[key] = number(item.substr(sp + 1), file, line, "component " + key);
  }
  return a;
}

Eigen::Isometry3d krl_pose(const Aggregate& a, const std::string& file, int line) {
  for (const char* k : {"X", "Y", "Z", "A", "B", "C"}) {
    if (!a.count(k)) bad(file, line, std::string("the frame has no ") + k);
  }
  for (const char* k : {"X", "Y", "Z"})
    position(a.at(k), file, line, std::string("component ") + k);
  for (const char* k : {"A", "B", "C"}) {
    if (std::fabs(a.at(k)) > kMaxAngle) {
      bad(file, line,
          std::string("component ") + k + " = " + format_shortest(a.at(k)) +
              " deg: an orientation angle lies within -360 to 360 deg");
    }
  }
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = kuka_abc(a.at("A"), a.at("B"), a.at("C"));
  t.translation() = Vec3(a.at("X"), a.at("Y"), a.at("Z"));
  return t;
}

struct KrlReader {
  Source source;
  std::filesystem::path dir;
  RobotProgram* out = nullptr;
  std::map<std::string, std::pair<Aggregate, std::string>> globals;  // main .dat
  double vel_cp = 2.0;                                               // m/s, KRL's default
  double vel_extax = 100.0;                                          // % of E1's max_velocity
  bool have_tool = false, have_base = false;
  int depth = 0;
  /// Modules read so far (upper case) -> where they were called ("the main program" for it): each
  /// part runs once (a part called 3000 times was read and replayed 3000 times, for minutes).
  std::map<std::string, std::string> called;

  /// Reads NAME.dat: declarations by upper-case name.
  std::map<std::string, std::pair<Aggregate, std::string>> read_dat(
      const std::filesystem::path& p) {
    const Text t = source.load(p);
    out->files.push_back(t.name);
    std::map<std::string, std::pair<Aggregate, std::string>> decl;
    for (std::size_t i = 0; i < t.lines.size(); ++i) {
      const int ln = static_cast<int>(i) + 1;
      const std::string s = code_of(t.lines[i], ';');
      const std::string u = upper(s);
      if (s.empty() || s[0] == '&' || u.rfind("DEFDAT", 0) == 0 || u == "ENDDAT") continue;
      if (u.rfind("DECL ", 0) != 0) bad(t.name, ln, "unknown KRL data line '" + s + "'");
      std::istringstream is(s.substr(5));
      std::string type, rest;
      is >> type;
      std::getline(is, rest);
      const std::size_t eq = rest.find('=');
      if (eq == std::string::npos) bad(t.name, ln, "a declaration needs '= {...}'");
      const std::string name = upper(trim(rest.substr(0, eq)));
      const std::string ut = upper(type);
      if (ut != "FRAME" && ut != "E6POS" && ut != "POS") {
        bad(t.name, ln, "unsupported KRL data type '" + type + "' (FRAME, POS, E6POS)");
      }
      if (const auto it = decl.find(name); it != decl.end()) {
        // (The second silently replaced the first: a target moved by hand was replayed as the
        // copy, a TOOL_EYE redeclared as the other.)
        bad(t.name, ln,
            "'" + trim(rest.substr(0, eq)) + "' is declared a second time (first on " +
                it->second.second + "); each name is declared once");
      }
      decl[name] = {krl_aggregate(rest.substr(eq + 1), t.name, ln),
                    t.name + ":" + std::to_string(ln)};
    }
    return decl;
  }

  /// `from` is the call ("wp.src:9"), empty for the main program.
  void read_src(const std::string& module, bool main, const std::string& from = "") {
    if (const auto it = called.find(upper(module)); it != called.end()) {
      throw InputError(from + ": calls " + module + ", which runs already (" + it->second +
                       "); a windplan program runs each part once");
    }
    called[upper(module)] = main ? "the main program" : "called on " + from;
    if (++depth > 8) throw InputError(from + ": calls " + module + " nested deeper than 8");
    const std::filesystem::path src = dir / (module + ".src");
    const std::filesystem::path dat = dir / (module + ".dat");
    std::map<std::string, std::pair<Aggregate, std::string>> local;
    if (main) {
      if (source.exists(dat)) globals = read_dat(dat);
    } else {
      if (!source.exists(src)) {
        throw IoError(from + ": calls " + module + ", but " + src.string() + " is missing");
      }
      if (source.exists(dat)) local = read_dat(dat);
    }
    const Text t = source.load(src);
    out->files.push_back(t.name);
    auto lookup = [&](const std::string& name, int ln) -> const std::pair<Aggregate, std::string>& {
      const std::string u = upper(name);
      if (local.count(u)) return local.at(u);
      if (globals.count(u)) return globals.at(u);
      bad(t.name, ln, "'" + name + "' is not declared in " + module + ".dat or the main .dat");
    };
    for (std::size_t i = 0; i < t.lines.size(); ++i) {
      const int ln = static_cast<int>(i) + 1;
      const std::string s = code_of(t.lines[i], ';');
      const std::string u = upper(s);
      if (s.empty() || s[0] == '&' || u.rfind("DEF ", 0) == 0 || u == "END") continue;
      if (s[0] == '$') {
        const std::size_t eq = s.find('=');
        if (eq == std::string::npos) bad(t.name, ln, "an assignment needs '='");
        const std::string var = upper(trim(s.substr(0, eq)));
        const std::string val = trim(s.substr(eq + 1));
        if (var == "$TOOL" || var == "$BASE") {
          const Eigen::Isometry3d f = krl_pose(lookup(val, ln).first, t.name, ln);
          (var == "$TOOL" ? out->tool : out->base) = f;
          (var == "$TOOL" ? have_tool : have_base) = true;
        } else if (var == "$VEL.CP") {
          vel_cp = number(val, t.name, ln, "$VEL.CP");
          if (!(vel_cp > 0.0)) bad(t.name, ln, "$VEL.CP must be > 0 m/s");
          if (vel_cp < 1e-6 || vel_cp > 10.0) {
            bad(t.name, ln,
                "$VEL.CP = " + val +
                    " m/s: a path speed lies within 1e-6 to 10 m/s (no arm "
                    "moves its tool faster; slower, one move would take days)");
          }
        } else if (var == "$VEL_EXTAX[1]") {
          vel_extax = number(val, t.name, ln, var);
          if (!(vel_extax > 0.0 && vel_extax <= 100.0))
            bad(t.name, ln, var + " must be in (0, 100]");
        } else if (var == "$APO.CDIS" || var == "$ACC.CP") {
          number(val, t.name, ln, var);
        } else {
          bad(t.name, ln, "unsupported system variable " + var);
        }
        continue;
      }
      std::istringstream is(s);
      std::string word, target, approx;
      is >> word >> target >> approx;
      const std::string uw = upper(word);
      if (uw == "PTP" || uw == "LIN") {
        if (target.empty()) bad(t.name, ln, uw + " needs a target");
        if (!approx.empty() && upper(approx) != "C_DIS" && upper(approx) != "C_PTP") {
          bad(t.name, ln, "unsupported approximation '" + approx + "'");
        }
        if (!have_tool || !have_base) bad(t.name, ln, "a move before $TOOL and $BASE are set");
        const Aggregate& a = lookup(target, ln).first;
        RobotProgramTarget r;
        r.file = t.name;
        r.line = ln;
        r.joint_move = uw == "PTP";
        r.pose = krl_pose(a, t.name, ln);
        if (!a.count("E1")) bad(t.name, ln, target + " has no E1 (the positioner)");
        r.e1 = a.at("E1");
        if (std::fabs(r.e1) > kMaxE1) {
          bad(t.name, ln, target + "'s E1 = " + format_shortest(r.e1) + " deg is beyond 1e9 deg");
        }
        r.status = a.count("S") ? status(a.at("S"), t.name, ln, target + "'s S") : -1;
        r.vel_cp = vel_cp;
        r.vel_extax = vel_extax;
        out->targets.push_back(r);
        continue;
      }
      // A call of a part: NAME( )
      const std::size_t par = s.find('(');
      if (par != std::string::npos &&
          (trim(s.substr(par)) == "( )" || trim(s.substr(par)) == "()")) {
        read_src(trim(s.substr(0, par)), false, t.name + ":" + std::to_string(ln));
        continue;
      }
      bad(t.name, ln, "unknown KRL statement '" + s + "'");
    }
    --depth;
  }
};

// ---- RAPID ----

struct Value {
  bool list = false;
  std::string atom;  // a number, TRUE/FALSE or a "string"
  std::vector<Value> items;
};

struct ValueParser {
  const std::string& s;
  std::size_t i = 0;
  std::string file;
  int line = 0;
  void ws() {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
  }
  Value parse() {
    ws();
    Value v;
    if (i < s.size() && s[i] == '[') {
      v.list = true;
      ++i;
      ws();
      if (i < s.size() && s[i] == ']') {
        ++i;
        return v;
      }
      while (true) {
        v.items.push_back(parse());
        ws();
        if (i < s.size() && s[i] == ',') {
          ++i;
          continue;
        }
        if (i < s.size() && s[i] == ']') {
          ++i;
          return v;
        }
        bad(file, line, "malformed RAPID aggregate near column " + std::to_string(i + 1));
      }
    }
    const std::size_t a = i;
    if (i < s.size() && s[i] == '"') {
      ++i;
      while (i < s.size() && s[i] != '"') ++i;
      if (i >= s.size()) bad(file, line, "unterminated string");
      ++i;
    } else {
      while (i < s.size() && s[i] != ',' && s[i] != ']' && s[i] != ';') ++i;
    }
    v.atom = trim(s.substr(a, i - a));
    if (v.atom.empty()) bad(file, line, "empty value in a RAPID aggregate");
    return v;
  }
};

double num(const Value& v, const std::string& file, int line, const std::string& what) {
  if (v.list) bad(file, line, what + ": expected a number, got a list");
  return number(v.atom, file, line, what);
}

const Value& item(const Value& v, std::size_t k, std::size_t n, const std::string& file, int line,
                  const std::string& what) {
  if (!v.list || v.items.size() != n) {
    bad(file, line, what + ": expected a list of " + std::to_string(n));
  }
  return v.items[k];
}

Eigen::Isometry3d rapid_pose(const Value& v, const std::string& file, int line,
                             const std::string& what) {
  const Value& p = item(v, 0, 2, file, line, what);
  const Value& q = item(v, 1, 2, file, line, what);
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (int k = 0; k < 3; ++k) {
    t.translation()(k) = position(num(item(p, k, 3, file, line, what + " pos"), file, line, what),
                                  file, line, what + " pos[" + std::to_string(k) + "]");
  }
  const Eigen::Quaterniond qq(num(item(q, 0, 4, file, line, what + " orient"), file, line, what),
                              num(q.items[1], file, line, what), num(q.items[2], file, line, what),
                              num(q.items[3], file, line, what));
  if (std::fabs(qq.norm() - 1.0) > 1e-4) bad(file, line, what + ": the quaternion is not unit");
  t.linear() = qq.normalized().toRotationMatrix();
  return t;
}

/// Splits at top-level commas (outside brackets and quotes).
std::vector<std::string> split_args(const std::string& s) {
  std::vector<std::string> out;
  int depth = 0;
  bool quoted = false;
  std::string cur;
  for (char c : s) {
    if (c == '"') quoted = !quoted;
    if (!quoted && c == '[') ++depth;
    if (!quoted && c == ']') --depth;
    if (!quoted && depth == 0 && c == ',') {
      out.push_back(trim(cur));
      cur.clear();
      continue;
    }
    cur += c;
  }
  out.push_back(trim(cur));
  return out;
}

struct RapidReader {
  Source source;
  std::filesystem::path dir;
  RobotProgram* out = nullptr;
  std::map<std::string, Eigen::Isometry3d> tools, wobjs;
  std::map<std::string, Value> robtargets;
  std::map<std::string, std::string> declared;  // upper-case name -> "file:line"
  std::map<std::string, std::string> called;    // module (upper case) -> its call

  /// `from` is the call ("wp.mod:7"), empty for the main module.
  void read_module(const std::string& name, bool main, const std::string& from = "") {
    const std::filesystem::path file = dir / (name + ".mod");
    if (const auto it = called.find(upper(name)); it != called.end()) {
      throw InputError(from + ": calls " + name + ", which runs already (" + it->second +
                       "); a windplan program runs each part once");
    }
    called[upper(name)] = main ? "the main module" : "called on " + from;
    if (!main && !source.exists(file)) {
      throw IoError(from + ": calls " + name + ", but " + file.string() + " is missing");
    }
    const Text t = source.load(file);
    out->files.push_back(t.name);
    bool in_proc = false;
    for (std::size_t i = 0; i < t.lines.size(); ++i) {
      const int ln = static_cast<int>(i) + 1;
      std::string s = code_of(t.lines[i], '!');
      if (s.empty()) continue;
      const std::string u = upper(s);
      if (u.rfind("MODULE ", 0) == 0 || u == "ENDMODULE") continue;
      if (u.rfind("PROC ", 0) == 0) {
        in_proc = true;
        continue;
      }
      if (u == "ENDPROC") {
        in_proc = false;
        continue;
      }
      if (s.back() != ';') bad(t.name, ln, "a RAPID statement ends with ';'");
      s.pop_back();
      std::istringstream is(s);
      std::string w1, w2;
      is >> w1 >> w2;
      const std::string u1 = upper(w1), u2 = upper(w2);
      if (!in_proc && (u1 == "PERS" || u1 == "CONST" || u1 == "VAR")) {
        const std::size_t eq = s.find(":=");
        if (eq == std::string::npos) bad(t.name, ln, "a declaration needs ':='");
        std::istringstream names(s.substr(0, eq));
        std::string kw, type, var;
        names >> kw >> type >> var;
        const std::string rhs = s.substr(eq + 2);
        ValueParser vp{rhs, 0, t.name, ln};
        const Value v = vp.parse();
        const std::string ut = upper(type);
        if (const auto it = declared.find(upper(var)); it != declared.end()) {
          bad(t.name, ln,
              "'" + var + "' is declared a second time (first on " + it->second +
                  "); each name is declared once");
        }
        declared[upper(var)] = t.name + ":" + std::to_string(ln);
        if (ut == "TOOLDATA") {
          tools[upper(var)] =
              rapid_pose(item(v, 1, 3, t.name, ln, "tooldata"), t.name, ln, "tframe");
        } else if (ut == "WOBJDATA") {
          const Eigen::Isometry3d uf =
              rapid_pose(item(v, 3, 5, t.name, ln, "wobjdata"), t.name, ln, "uframe");
          const Eigen::Isometry3d of = rapid_pose(v.items[4], t.name, ln, "oframe");
          wobjs[upper(var)] = uf * of;
        } else if (ut == "ROBTARGET") {
          robtargets[upper(var)] = v;
        } else {
          bad(t.name, ln, "unsupported RAPID data type '" + type + "'");
        }
        continue;
      }
      if (!in_proc) bad(t.name, ln, "a statement outside a PROC: '" + s + "'");
      if (u1 == "MOVEL" || u1 == "MOVEJ") {
        const std::vector<std::string> args = split_args(trim(s.substr(w1.size())));
        if (args.size() != 4) {
          bad(t.name, ln,
              w1 + " needs target, speed, zone and tool\\WObj (got " + std::to_string(args.size()) +
                  " arguments)");
        }
        Value target;
        if (!args[0].empty() && args[0][0] == '[') {
          ValueParser vp{args[0], 0, t.name, ln};
          target = vp.parse();
        } else if (robtargets.count(upper(args[0]))) {
          target = robtargets.at(upper(args[0]));
        } else {
          bad(t.name, ln, "robtarget '" + args[0] + "' is not declared");
        }
        RobotProgramTarget r;
        r.file = t.name;
        r.line = ln;
        r.joint_move = u1 == "MOVEJ";
        if (!target.list || target.items.size() != 4) bad(t.name, ln, "a robtarget has 4 parts");
        Value pose;
        pose.list = true;
        pose.items = {target.items[0], target.items[1]};
        r.pose = rapid_pose(pose, t.name, ln, "robtarget");
        const Value& cf = item(target, 2, 4, t.name, ln, "robtarget");
        r.status = status(num(item(cf, 3, 4, t.name, ln, "confdata"), t.name, ln, "cfx"), t.name,
                          ln, "cfx");
        const Value& ext = item(target, 3, 4, t.name, ln, "robtarget");
        r.e1 = num(item(ext, 0, 6, t.name, ln, "extjoint"), t.name, ln, "eax_a");
        if (std::fabs(r.e1) >= 9e8) bad(t.name, ln, "eax_a (the positioner E1) is not set");
        const std::string speed = args[1];
        const std::size_t tt = upper(speed).find("\\T:=");
        if (tt != std::string::npos) {
          r.time = number(speed.substr(tt + 4), t.name, ln, "\\T");
          if (!(r.time >= 0.0)) bad(t.name, ln, "\\T must be >= 0 s");
          if (r.time > 86400.0) {
            bad(t.name, ln, "\\T = " + format_shortest(r.time) + " s: one move of more than a day");
          }
        }
        if (upper(speed).rfind("V", 0) != 0) bad(t.name, ln, "unknown speeddata '" + speed + "'");
        const std::string tool_arg = args[3];
        const std::size_t wo = upper(tool_arg).find("\\WOBJ:=");
        if (wo == std::string::npos) bad(t.name, ln, "the move names no \\WObj (the positioner)");
        const std::string tool = upper(trim(tool_arg.substr(0, wo)));
        const std::string wobj = upper(trim(tool_arg.substr(wo + 7)));
        if (!tools.count(tool)) bad(t.name, ln, "tooldata '" + tool + "' is not declared");
        if (!wobjs.count(wobj)) bad(t.name, ln, "wobjdata '" + wobj + "' is not declared");
        out->tool = tools.at(tool);
        out->base = wobjs.at(wobj);
        out->targets.push_back(r);
        continue;
      }
      if (w2.empty() && main) {  // a call of a part
        read_module(trim(w1), false, t.name + ":" + std::to_string(ln));
        continue;
      }
      if (w2.empty() && !main) {
        bad(t.name, ln, "'" + s + "': a part calls no other module (only the main module does)");
      }
      bad(t.name, ln, "unknown RAPID statement '" + s + "'");
    }
  }
};

}  // namespace

namespace {

RobotProgram read_any(const std::filesystem::path& main, const std::string& dialect,
                      const std::map<std::string, std::string>* memory) {
  RobotProgram p;
  p.dialect = dialect;
  const std::string ext = main.extension().string();
  if (dialect == "krl") {
    if (ext != ".src") throw InputError(main.string() + ": a KRL program is a .src file");
    KrlReader r;
    r.source.memory = memory;
    r.dir = main.parent_path();
    r.out = &p;
    r.read_src(main.stem().string(), true);
  } else if (dialect == "rapid") {
    if (ext != ".mod") throw InputError(main.string() + ": a RAPID program is a .mod file");
    RapidReader r;
    r.source.memory = memory;
    r.dir = main.parent_path();
    r.out = &p;
    r.read_module(main.stem().string(), true);
  } else {
    throw ConfigError("machine.robot.dialect: unknown robot dialect '" + dialect + "'");
  }
  if (p.targets.empty()) throw InputError(main.string() + ": the program has no moves");
  return p;
}

}  // namespace

RobotProgram read_robot_program(const std::filesystem::path& main, const std::string& dialect) {
  return read_any(main, dialect, nullptr);
}

RobotProgram read_robot_program(const std::map<std::string, std::string>& files,
                                const std::string& main, const std::string& dialect) {
  return read_any(main, dialect, &files);
}

}  // namespace windplan
