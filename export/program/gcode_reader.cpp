#include "export/program/gcode_reader.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

#include "geometry/base/errors.h"

namespace windplan {

namespace {

constexpr double kMaxWordValue = 1e9;      // any word's value but F's
constexpr double kMaxLinearTravel = 1e5;   // mm: a linear axis beyond 100 m is no winder's
constexpr std::size_t kMaxCallDepth = 10;  // nested M98 calls

struct Word {
  char letter;
  double value;
  std::string text;
};

struct Line {
  int number = 0;  // 1-based
  std::vector<Word> words;
  std::string comment;  // the text of its comments, lower case
};

// The radius of "eye radius R mm" in a comment (lower case): > 0 when found, 0 when the comment
// does not name one, -1 when it names one that is not a positive decimal number of mm, -2 when it
// names more than one. R is written in decimal (digits, a point, an exponent): strtod alone also
// read "0x49" as 73 mm, and "inf" or "nan".
double eye_radius_in(const std::string& comment) {
  const std::string key = "eye radius";
  const std::size_t at = comment.find(key);
  if (at == std::string::npos) return 0.0;
  if (comment.find(key, at + key.size()) != std::string::npos) return -2.0;
  std::size_t i = at + key.size();
  while (i < comment.size() && comment[i] == ' ') ++i;
  const std::size_t start = i;
  while (i < comment.size() &&
         (std::isdigit(static_cast<unsigned char>(comment[i])) || comment[i] == '.' ||
          comment[i] == '+' || comment[i] == '-' || comment[i] == 'e')) {
    ++i;
  }
  const std::string token = comment.substr(start, i - start);
  char* end = nullptr;
  const double r = std::strtod(token.c_str(), &end);
  if (token.empty() || end != token.c_str() + token.size() || !std::isfinite(r) || !(r > 0.0) ||
      r > kMaxLinearTravel) {
    return -1.0;
  }
  while (i < comment.size() && comment[i] == ' ') ++i;
  if (comment.compare(i, 2, "mm") != 0) return -1.0;
  return r;
}

std::string code_of(const Word& w) {
  std::string s(1, w.letter);
  const double v = w.value;
  // (A cast of X1e10 to long long was undefined behaviour: only small whole numbers are codes.)
  if (v == std::floor(v) && std::fabs(v) < 1e6)
    return s + std::to_string(static_cast<long long>(v));
  return s + w.text;
}

}  // namespace

GcodeProgram read_gcode(const std::string& text, const MachineOptions& machine,
                        const std::string& name) {
  const std::string& dialect = machine.gcode.dialect;
  const bool fanuc = dialect == "fanuc", marlin = dialect == "marlin";
  const bool lathe2 = machine.kind == "lathe2";
  auto fail = [&](int line, const std::string& msg) -> void {
    throw InputError(name + ":" + std::to_string(line) + ": " + msg);
  };
  auto other = [&](int line, const std::string& what, const std::string& who) {
    fail(line, what + " belongs to a " + who + " program; the job's dialect is " + dialect +
                   " (machine.gcode.dialect)");
  };
  // Axes: letter -> (value index A X Y B, options).
  struct AxisRef {
    int index;
    const AxisOptions* o;
  };
  std::map<char, AxisRef> axes;
  axes[machine.x.letter[0]] = {1, &machine.x};
  axes[machine.a.letter[0]] = {0, &machine.a};
  if (!lathe2) {
    axes[machine.y.letter[0]] = {2, &machine.y};
    axes[machine.b.letter[0]] = {3, &machine.b};
  }

  // Tokenise; programs by O label (fanuc) in order of appearance.
  std::vector<Line> lines;
  std::map<int, std::size_t> labels;  // O number -> first line index after it
  std::istringstream in(text);
  std::string raw;
  int number = 0;
  while (std::getline(in, raw)) {
    ++number;
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();
    if (raw.find('\r') != std::string::npos) {
      // Read as one line, a CR-only program was replayed as one block.
      fail(number,
           "a carriage return (CR) inside the line: the program has CR-only line ends "
           "(old Mac style); convert them to LF or CR LF");
    }
    std::string s, comment;
    int depth = 0;
    for (std::size_t k = 0; k < raw.size(); ++k) {
      const char c = raw[k];
      if (c == ';' && depth == 0) {
        if (fanuc) other(number, "a ';' comment", "linuxcnc or marlin");
        comment += raw.substr(k + 1);
        break;
      }
      if (c == '(') {
        if (marlin) other(number, "a '( )' comment", "linuxcnc or fanuc");
        ++depth;
        continue;
      }
      if (c == ')') {
        if (depth == 0) fail(number, "')' without '('");
        --depth;
        continue;
      }
      if (depth == 0) {
        s += c;
      } else {
        comment += c;
      }
    }
    if (depth != 0) fail(number, "unclosed '(' comment");
    Line ln;
    ln.number = number;
    for (char& c : comment) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    ln.comment = comment;
    if (ln.comment.find("eye radius") != std::string::npos) {
      // lathe2's operator stop names the eye radius of the layer that follows (gcode.h).
      if (!lathe2) {
        fail(number,
             "an eye radius set by hand: only a lathe2 (no cross-feed) sets its eye so; a " +
                 machine.kind + " moves it with its axes");
      }
      const double named = eye_radius_in(ln.comment);
      if (named == -2.0) {
        fail(number,
             "the comment names the eye radius more than once; an operator stop sets one radius "
             "(\"eye radius R mm\")");
      }
      if (named < 0.0) {
        fail(number,
             "the comment names an eye radius but not as \"eye radius R mm\" with R a decimal "
             "number, 0 < R <= 100000");
      }
    }
    std::size_t i = 0;
    while (i < s.size()) {
      const unsigned char c = static_cast<unsigned char>(s[i]);
      if (std::isspace(c)) {
        ++i;
        continue;
      }
      if (s[i] == '%') {
        if (marlin) other(number, "a '%' line", "linuxcnc or fanuc");
        ++i;
        continue;
      }
      if (!std::isalpha(c)) fail(number, std::string("unexpected character '") + s[i] + "'");
      const char letter = static_cast<char>(std::toupper(c));
      ++i;
      const std::size_t start = i;
      while (i < s.size() && (std::isdigit(static_cast<unsigned char>(s[i])) || s[i] == '.' ||
                              s[i] == '-' || s[i] == '+')) {
        ++i;
      }
      const std::string num = s.substr(start, i - start);
      char* end = nullptr;
      const double v = std::strtod(num.c_str(), &end);
      if (num.empty() || end != num.c_str() + num.size() || !std::isfinite(v)) {
        fail(number, std::string("word ") + letter + " without a valid number");
      }
      if (letter != 'F' && std::fabs(v) > kMaxWordValue) {
        // (F is exempt: in inverse time a tiny move's F = 1 / minutes is legitimately huge.)
        fail(number, std::string("word ") + letter + num +
                         ": the number is out of range (|value| > 1e9, which no controller reads)");
      }
      ln.words.push_back({letter, v, num});
    }
    if (ln.words.empty()) {
      if (eye_radius_in(ln.comment) > 0.0) {
        fail(number,
             "an eye radius is set by hand at an operator stop: name it on an M0 line without "
             "axis words");
      }
      continue;
    }
    if (ln.words[0].letter == 'O') {
      if (!fanuc) other(number, "an O program label", "fanuc");
      labels[static_cast<int>(ln.words[0].value)] = lines.size();
      continue;
    }
    lines.push_back(ln);
  }

  GcodeProgram prog;
  double value[4] = {0, 0, 0, 0};
  bool known[4] = {false, false, false, false};
  const bool needed[4] = {true, true, !lathe2, !lathe2};
  double a_shift = 0.0;  // Marlin G92: planner A = word + shift
  double feed = 0.0;
  bool have_feed = false;
  int motion = -1;  // modal 0 / 1
  bool inverse = false;
  double eye_radius = 0.0;  // lathe2: set at the last operator stop (0: none yet)
  std::vector<std::size_t> stack;
  std::size_t pc = 0;
  int steps = 0;
  while (pc < lines.size()) {
    if (++steps > 50000000) fail(lines[pc].number, "the program does not end (call loop)");
    const Line& ln = lines[pc++];
    bool move = false, g92 = false;
    int call = -1;
    double newv[4] = {value[0], value[1], value[2], value[3]};
    bool set[4] = {false, false, false, false};
    bool end = false, ret = false, stop = false;
    bool f_word = false;
    int motion_words = 0;
    for (const Word& w : ln.words) {
      const std::string code = code_of(w);
      if (w.letter == 'N') {
        if (!fanuc) other(ln.number, "an N line number", "fanuc");
        continue;
      }
      if (w.letter == 'G') {
        if (code == "G0" || code == "G00") {
          motion = 0;
          if (++motion_words > 1) fail(ln.number, "two motion codes (G0, G1) on one line");
        } else if (code == "G1" || code == "G01") {
          motion = 1;
          if (++motion_words > 1) fail(ln.number, "two motion codes (G0, G1) on one line");
        } else if (code == "G21" || code == "G90") {
        } else if (code == "G94") {
          inverse = false;
        } else if (code == "G93") {
          if (marlin) other(ln.number, "G93 (inverse time)", "linuxcnc or fanuc");
          inverse = true;
          prog.inverse_time = true;
        } else if (code == "G92") {
          if (!marlin) other(ln.number, "G92", "marlin");
          g92 = true;
        } else if (code == "G20") {
          fail(ln.number, "G20 (inch units): windplan programs are in mm (G21)");
        } else if (code == "G91") {
          fail(ln.number, "G91 (incremental): windplan programs are absolute (G90)");
        } else {
          fail(ln.number, "unknown code " + code + " for a " + dialect + " winder program");
        }
        continue;
      }
      if (w.letter == 'M') {
        if (code == "M2" || code == "M02") {
          if (fanuc) other(ln.number, code, "linuxcnc or marlin");
          end = true;
        } else if (code == "M30") {
          if (marlin) other(ln.number, code, "linuxcnc or fanuc");
          end = true;
        } else if (code == "M84") {
          if (!marlin) other(ln.number, code, "marlin");
          end = true;
        } else if (code == "M0" || code == "M00") {
          // A pause between layers (the operator ties off and cuts): no motion. lathe2: the
          // operator sets the eye radius its comment names.
          stop = true;
        } else if (code == "M98") {
          if (!fanuc) other(ln.number, code, "fanuc");
          call = 0;
        } else if (code == "M99") {
          if (!fanuc) other(ln.number, code, "fanuc");
          ret = true;
        } else {
          fail(ln.number, "unknown code " + code + " for a " + dialect + " winder program");
        }
        continue;
      }
      if (w.letter == 'P') {
        if (call != 0) fail(ln.number, "P word without M98");
        call = static_cast<int>(w.value);
        continue;
      }
      if (w.letter == 'F') {
        if (!(w.value > 0.0)) fail(ln.number, "F must be > 0 (got " + w.text + ")");
        if (f_word) fail(ln.number, "two F words on one line");
        f_word = true;
        feed = w.value;
        have_feed = true;
        continue;
      }
      const auto it = axes.find(w.letter);
      if (it == axes.end()) {
        fail(ln.number, std::string("unknown word ") + w.letter + w.text + " (a " + machine.kind +
                            " machine has axes " +
                            (lathe2 ? machine.x.letter + " " + machine.a.letter
                                    : machine.x.letter + " " + machine.y.letter + " " +
                                          machine.a.letter + " " + machine.b.letter) +
                            ")");
      }
      const AxisRef& ax = it->second;
      if (set[ax.index]) {
        fail(ln.number, "two " + ax.o->letter + " words on one line (LinuxCNC refuses it too)");
      }
      if (ax.index == 1 || ax.index == 2) {
        if (std::fabs(w.value) > kMaxLinearTravel) {
          fail(ln.number, "axis " + ax.o->letter + " moves to " + w.text +
                              " mm, beyond 100 m: no winder's travel (a value in microns, or a "
                              "typo?)");
        }
      }
      if (g92) {
        if (ax.index != 0 || !marlin) fail(ln.number, "G92 re-zeroes the spindle axis only");
        // The machine's A becomes w.value here: shift = planner A - sign * word.
        a_shift = value[0] - ax.o->sign * w.value;
        continue;
      }
      double v;
      if (marlin && ax.index == 0) {
        v = ax.o->sign * w.value + a_shift;  // sign = +-1: its own inverse
      } else {
        v = ax.o->sign * (w.value - ax.o->offset);
      }
      const double machine_value = ax.o->sign * v + ax.o->offset;
      if (!(marlin && ax.index == 0) &&
          (machine_value < ax.o->min - 1e-9 || machine_value > ax.o->max + 1e-9)) {
        fail(ln.number, "axis " + ax.o->letter + " moves to " + w.text + ", outside its travel [" +
                            std::to_string(ax.o->min) + ", " + std::to_string(ax.o->max) +
                            "] (machine.axes)");
      }
      newv[ax.index] = v;
      set[ax.index] = true;
      move = true;
    }
    if (call > 0) {
      const auto lab = labels.find(call);
      if (lab == labels.end())
        fail(ln.number, "M98 calls O" + std::to_string(call) + ", not in the program");
      // Fanuc nests subprograms a few levels deep (4 on most controls); a call of itself
      // recursed until the step bound, gigabytes later (found by fuzz_gcode).
      if (stack.size() >= kMaxCallDepth) {
        fail(ln.number, "M98 calls O" + std::to_string(call) + " nested more than " +
                            std::to_string(kMaxCallDepth) +
                            " deep (a subprogram that calls itself?)");
      }
      stack.push_back(pc);
      pc = lab->second;
      continue;
    }
    if (call == 0) fail(ln.number, "M98 without a P program number");
    if (const double r = eye_radius_in(ln.comment); r > 0.0) {
      if (!stop || move) {
        fail(ln.number,
             "an eye radius is set by hand at an operator stop: name it on an M0 line without "
             "axis words");
      }
      eye_radius = r;
      prog.eye_stops.push_back({ln.number, r});
    }
    if (move && !g92) {
      if (motion < 0) fail(ln.number, "an axis word before any G0 or G1");
      for (int k = 0; k < 4; ++k) {
        if (set[k]) known[k] = true;
        if (needed[k] && !known[k]) {
          fail(ln.number, "the first move leaves an axis undefined (give every axis word)");
        }
      }
      if (motion == 1 && !have_feed) fail(ln.number, "G1 without a feed (F)");
      if (motion == 1 && inverse && !f_word) {
        fail(ln.number,
             "G1 without an F word in inverse time mode (G93): each move gives its "
             "own F = 1 / minutes (LinuxCNC refuses it too)");
      }
      GcodeBlock b;
      b.line = ln.number;
      b.rapid = motion == 0;
      b.a = newv[0];
      b.x = newv[1];
      b.y = newv[2];
      b.b = newv[3];
      b.feed = feed;
      b.inverse_time = inverse;
      b.eye_radius = eye_radius;
      prog.blocks.push_back(b);
      for (int k = 0; k < 4; ++k) value[k] = newv[k];
    }
    if (ret) {
      if (stack.empty()) fail(ln.number, "M99 outside a subprogram");
      pc = stack.back();
      stack.pop_back();
      continue;
    }
    if (end) {
      prog.ended = true;
      // Anything after the end code is never run: a forgotten M2 in the middle is an error
      // (fanuc: subprograms, each after its O label, follow M30).
      bool label_next = false;
      for (const auto& kv : labels) label_next = label_next || kv.second == pc;
      if (pc < lines.size() && stack.empty() && !(fanuc && label_next)) {
        fail(ln.number, "the end code here stops the program, but " +
                            std::to_string(lines.size() - pc) + " more line(s) follow (from line " +
                            std::to_string(lines[pc].number) +
                            ") that would never run; remove the end code or the lines");
      }
      break;
    }
  }
  if (!prog.ended) {
    fail(number, std::string("the program has no end code (") +
                     (marlin  ? "M84"
                      : fanuc ? "M30"
                              : "M2") +
                     ")");
  }
  return prog;
}

}  // namespace windplan
