#include "export/program/gcode.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "geometry/base/errors.h"
#include "windplan_version.h"

namespace windplan {

namespace {

// Values are handled as integer ticks of 1e-4 so that Marlin's G92 shifts never drift.
long long ticks(double v) { return std::llround(v * 1e4); }

std::string format_ticks(long long t) {
  char buf[48];
  const long long a = t < 0 ? -t : t;
  std::snprintf(buf, sizeof buf, "%s%lld.%04lld", t < 0 ? "-" : "", a / 10000, a % 10000);
  return buf;
}

// Keeps printable characters that are safe inside a comment of every dialect.
std::string comment_text(const std::string& s, bool upper) {
  std::string out;
  for (char ch : s) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c >= 0x7f || ch == '(' || ch == ')' || ch == ';' || ch == '%') {
      out += ' ';
    } else {
      out += upper ? static_cast<char>(std::toupper(c)) : ch;
    }
  }
  return out;
}

class Writer {
 public:
  Writer(const std::string& dialect) : fanuc_(dialect == "fanuc"), marlin_(dialect == "marlin") {}
  void comment(const std::string& s) {
    if (marlin_) {
      out_ << "; " << comment_text(s, false) << "\n";
    } else {
      out_ << "(" << comment_text(s, fanuc_) << ")\n";
    }
  }
  void line(const std::string& s) {
    if (fanuc_) {
      out_ << "N" << n_ << " ";
      n_ = n_ >= 99999 ? 1 : n_ + 1;
    }
    out_ << s << "\n";
  }
  // A line with a comment after its words (an operator stop's instruction).
  void line(const std::string& s, const std::string& c) {
    if (marlin_) {
      line(s + " ; " + comment_text(c, false));
    } else {
      line(s + " (" + comment_text(c, fanuc_) + ")");
    }
  }
  void raw(const std::string& s) { out_ << s << "\n"; }
  void restart_numbers() { n_ = 1; }
  std::string str() const { return out_.str(); }

 private:
  bool fanuc_, marlin_;
  int n_ = 1;
  std::ostringstream out_;
};

}  // namespace

std::string format_fixed4(double v) { return format_ticks(ticks(v)); }

std::string eye_radius_comment(double radius_mm) {
  return "eye radius " + format_fixed4(radius_mm) + " mm: set the eye by hand, then cycle start";
}

std::string gcode_extension(const std::string& dialect) {
  if (dialect == "marlin") return ".gcode";
  if (dialect == "fanuc") return ".nc";
  return ".ngc";
}

std::string gcode_program(const Motion& motion, const std::string& job_name,
                          const MachineOptions& opts) {
  if (opts.kind == "robot") {
    throw InputError("machine.kind: robot has no G-code output (see eye_pose.csv)");
  }
  const std::string& dialect = opts.gcode.dialect;
  const bool fanuc = dialect == "fanuc", marlin = dialect == "marlin";
  const bool lathe2 = opts.kind == "lathe2";
  // Word order X Y A B; lathe2 drives X and A only. Index into the state's values A X Y B.
  struct Ax {
    const AxisOptions* o;
    int value;
  };
  std::vector<Ax> axes = {{&opts.x, 1}};
  if (!lathe2) axes.push_back({&opts.y, 2});
  axes.push_back({&opts.a, 0});
  if (!lathe2) axes.push_back({&opts.b, 3});

  std::vector<int> circuit_starts;  // indices into motion.states
  for (std::size_t i = 0; i < motion.states.size(); ++i) {
    if (i == 0 || motion.states[i].ordinal != motion.states[i - 1].ordinal) {
      circuit_starts.push_back(static_cast<int>(i));
    }
  }
  const int n_circuits = static_cast<int>(circuit_starts.size());
  if (fanuc && opts.gcode.program_number + n_circuits > 9999) {
    throw InputError("machine.gcode.program_number: " + std::to_string(n_circuits) +
                     " circuits need Fanuc program numbers up to " +
                     std::to_string(opts.gcode.program_number + n_circuits) + " > 9999");
  }

  Writer w(dialect);
  const bool inverse = motion.inverse_time;
  if (!marlin) w.raw("%");
  if (fanuc) {
    w.raw("O" + std::to_string(opts.gcode.program_number) + " (WINDPLAN " + WINDPLAN_VERSION +
          " JOB " + comment_text(job_name, true) + ")");
  } else {
    w.comment(std::string("windplan ") + WINDPLAN_VERSION + ", job " + job_name);
  }
  w.comment("machine " + opts.kind + ", dialect " + dialect +
            ", units: mm for linear axes, deg for rotary axes, 4 decimals");
  w.comment(inverse ? std::string("feed G93 inverse time: F = 1 / move time [1/min]")
                    : std::string("feed G94: F = combined axis distance per minute, deg as mm"));
  {
    char buf[160];
    std::snprintf(buf, sizeof buf, "circuits %d, moves %zu, wind time %.3f s", n_circuits,
                  motion.states.size(), motion.wind_time);
    w.comment(buf);
  }
  std::string axis_list;
  for (const Ax& a : axes) {
    static const char* names[4] = {"spindle", "carriage", "cross-feed", "eye rotation"};
    axis_list += (axis_list.empty() ? "" : ", ") + a.o->letter + " = " + names[a.value];
  }
  w.comment("axes: " + axis_list);
  if (marlin) {
    w.line("G21");
    w.line("G90");
    w.line("G94");
  } else {
    w.line(std::string("G21 G90 ") + (inverse ? "G93" : "G94"));
  }

  std::vector<long long> last(axes.size(), 0);
  std::vector<bool> known(axes.size(), false);
  long long a_shift = 0;  // Marlin: machine ticks of the spindle's G92 zero
  auto motion_line = [&](const MachineState& st, bool rapid) {
    const double value[4] = {st.a_deg, st.x_mm, st.y_mm, st.b_deg};
    std::string s = rapid ? "G0" : "G1";
    bool any = false;
    for (std::size_t i = 0; i < axes.size(); ++i) {
      const Ax& a = axes[i];
      long long t;
      if (marlin && a.value == 0) {
        t = ticks(a.o->sign * value[0]) - a_shift;
      } else {
        t = ticks(a.o->sign * value[a.value] + a.o->offset);
      }
      if (!known[i] || t != last[i] || (i + 1 == axes.size() && !any)) {
        s += " " + a.o->letter + format_ticks(t);
        any = true;
      }
      last[i] = t;
      known[i] = true;
    }
    if (!rapid) s += " F" + format_fixed4(st.feed);
    w.line(s);
  };

  // Layups: the layer whose first circuit with points circuit k is, or -1 (a layer's first
  // circuits may have no points, hence no states: its header goes before the first that has).
  auto layer_start = [&](int k) {
    const int ordinal = motion.states[circuit_starts[k]].ordinal;
    const int before = k > 0 ? motion.states[circuit_starts[k - 1]].ordinal : -1;
    for (std::size_t l = 0; l < motion.layers.size(); ++l) {
      const LayerSummary& L = motion.layers[l];
      if (L.circuit_count > 0 && before < L.first_circuit && L.first_circuit <= ordinal &&
          ordinal < L.first_circuit + L.circuit_count) {
        return static_cast<int>(l);
      }
    }
    return -1;
  };
  // Before a layer's first circuit k: the transition (tie off, cut, pause) and the layer comment.
  // lathe2 has no cross-feed: the operator sets the eye radius of the layer by hand at the stop.
  auto layer_header = [&](int l, int k) {
    const int n = static_cast<int>(motion.layers.size());
    const LayerSummary& L = motion.layers[l];
    if (l > 0) {
      w.comment("end of layer " + std::to_string(l) + " " + motion.layers[l - 1].name +
                ": tie off and cut the tow");
      if (lathe2) {
        w.line("M0", eye_radius_comment(motion.states[circuit_starts[k]].y_mm));
      } else {
        w.line("M0");
      }
    }
    w.comment("layer " + std::to_string(l + 1) + " of " + std::to_string(n) + ": " + L.name + ", " +
              L.kind + ", circuits " + std::to_string(L.first_circuit) + " to " +
              std::to_string(L.first_circuit + L.circuit_count - 1) +
              (l > 0 ? ": tie on the tow, cycle start, rapid to its first point" : ""));
  };

  auto circuit_body = [&](int k) {
    const int begin = circuit_starts[k];
    const int end =
        k + 1 < n_circuits ? circuit_starts[k + 1] : static_cast<int>(motion.states.size());
    const int layer = layer_start(k);
    if (!fanuc && layer >= 0) layer_header(layer, k);
    if (!fanuc) w.comment("circuit " + std::to_string(motion.states[begin].circuit));
    for (int i = begin; i < end; ++i) {
      motion_line(motion.states[i], i == 0 || (i == begin && layer > 0));
      if (marlin && i == begin) {
        // Re-zero the spindle at the circuit start: the machine's A becomes 0 here.
        for (std::size_t j = 0; j < axes.size(); ++j) {
          if (axes[j].value != 0) continue;
          a_shift += last[j];
          last[j] = 0;
          w.line("G92 " + axes[j].o->letter + "0");
        }
      }
    }
  };

  if (fanuc) {
    for (int k = 0; k < n_circuits; ++k) {
      if (const int layer = layer_start(k); layer >= 0) layer_header(layer, k);
      w.line("M98 P" + std::to_string(opts.gcode.program_number + 1 + k));
    }
    w.line("M30");
    for (int k = 0; k < n_circuits; ++k) {
      w.restart_numbers();
      w.raw("O" + std::to_string(opts.gcode.program_number + 1 + k) + " (CIRCUIT " +
            std::to_string(motion.states[circuit_starts[k]].circuit) + ")");
      circuit_body(k);
      w.line("M99");
    }
    w.raw("%");
  } else {
    for (int k = 0; k < n_circuits; ++k) circuit_body(k);
    if (marlin) {
      w.line("M84");
    } else {
      w.line("M2");
      w.raw("%");
    }
  }
  return w.str();
}

}  // namespace windplan
