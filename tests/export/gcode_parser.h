#pragma once
// A small G-code interpreter for the tests (test-only): follows what the three dialects windplan
// writes use: comments "( )" and ";", "%" lines, O program labels, N numbers, G0/G1 modal motion,
// G92 (position re-zeroing), M98 P.. / M99 subprogram calls and returns, M2/M30/M84 ends.
#include <cctype>
#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace windplan::test {

struct GcodeMove {
  bool rapid = false;
  std::map<char, double> pos;  ///< absolute machine coordinates (G92 shifts undone)
  double feed = 0.0;           ///< modal F at this move
};

struct ParsedGcode {
  std::vector<GcodeMove> moves;
  std::vector<std::string> codes;  ///< every G and M word, in execution order ("G93", "M98"...)
  bool ended = false;              ///< reached M2, M30 or M84
  int subprogram_calls = 0;
};

inline ParsedGcode parse_gcode(const std::string& text) {
  // Clean lines: no comments, no N words.
  std::vector<std::vector<std::pair<char, std::string>>> lines;
  std::map<int, std::size_t> labels;  // O number -> index of the first line after it
  std::istringstream in(text);
  std::string raw;
  while (std::getline(in, raw)) {
    std::string s;
    int depth = 0;
    for (char c : raw) {
      if (c == ';' && depth == 0) break;
      if (c == '(') ++depth;
      if (depth == 0) s += c;
      if (c == ')') --depth;
    }
    std::vector<std::pair<char, std::string>> words;
    std::size_t i = 0;
    while (i < s.size()) {
      if (std::isspace(static_cast<unsigned char>(s[i])) || s[i] == '%') {
        ++i;
        continue;
      }
      const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(s[i++])));
      std::string num;
      while (i < s.size() && (std::isdigit(static_cast<unsigned char>(s[i])) || s[i] == '.' ||
                              s[i] == '-' || s[i] == '+')) {
        num += s[i++];
      }
      if (num.empty()) throw std::runtime_error("word without a number in: " + raw);
      words.emplace_back(letter, num);
    }
    if (words.empty()) continue;
    if (words[0].first == 'O') {
      labels[std::atoi(words[0].second.c_str())] = lines.size();
      continue;
    }
    lines.push_back(words);
  }
  ParsedGcode out;
  std::map<char, double> logical, shift;
  double feed = 0.0;
  bool rapid = true;
  std::vector<std::size_t> stack;
  std::size_t pc = 0;
  while (pc < lines.size() && !out.ended) {
    const auto& words = lines[pc++];
    bool motion = false, g92 = false, call = false, ret = false;
    int target = 0;
    std::map<char, double> axes;
    for (const auto& [letter, num] : words) {
      const double v = std::atof(num.c_str());
      if (letter == 'N') continue;
      if (letter == 'G') {
        const int g = std::atoi(num.c_str());
        out.codes.push_back("G" + std::to_string(g));
        if (g == 0 || g == 1) {
          rapid = g == 0;
          motion = true;
        }
        if (g == 92) g92 = true;
      } else if (letter == 'M') {
        const int m = std::atoi(num.c_str());
        out.codes.push_back("M" + std::to_string(m));
        if (m == 2 || m == 30 || m == 84) out.ended = true;
        if (m == 98) call = true;
        if (m == 99) ret = true;
      } else if (letter == 'F') {
        feed = v;
      } else if (letter == 'P') {
        target = std::atoi(num.c_str());
      } else {
        axes[letter] = v;
      }
    }
    if (g92) {
      for (const auto& [a, v] : axes) {
        shift[a] = logical[a] + shift[a] - v;
        logical[a] = v;
      }
    } else if (!axes.empty()) {
      for (const auto& [a, v] : axes) logical[a] = v;
      motion = true;
    }
    if (motion && !axes.empty() && !g92) {
      GcodeMove m;
      m.rapid = rapid;
      m.feed = feed;
      for (const auto& [a, v] : logical) m.pos[a] = v + shift[a];
      out.moves.push_back(m);
    }
    if (call) {
      if (!labels.count(target)) throw std::runtime_error("M98 to a missing program");
      stack.push_back(pc);
      pc = labels[target];
      ++out.subprogram_calls;
    }
    if (ret) {
      if (stack.empty()) throw std::runtime_error("M99 outside a subprogram");
      pc = stack.back();
      stack.pop_back();
    }
  }
  return out;
}

}  // namespace windplan::test
