#pragma once
// A minimal, deterministic JSON writer (no dependency): keys are written in insertion order and
// doubles with a fixed number of significant digits, so two runs give identical bytes.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace windplan {

class JsonWriter {
 public:
  explicit JsonWriter(int indent = 2, int digits = 12) : indent_(indent), digits_(digits) {}

  JsonWriter& begin_object() { return open('{'); }
  JsonWriter& end_object() { return close('}'); }
  JsonWriter& begin_array() { return open('['); }
  JsonWriter& end_array() { return close(']'); }
  /// The key of the next value in the current object.
  JsonWriter& key(const std::string& k) {
    separate();
    out_ += quote(k);
    out_ += indent_ > 0 ? ": " : ":";
    after_key_ = true;
    return *this;
  }
  JsonWriter& value(const std::string& s) { return raw(quote(s)); }
  JsonWriter& value(const char* s) { return raw(quote(s)); }
  JsonWriter& value(bool b) { return raw(b ? "true" : "false"); }
  JsonWriter& value(int i) { return raw(std::to_string(i)); }
  JsonWriter& value(long i) { return raw(std::to_string(i)); }
  JsonWriter& value(long long i) { return raw(std::to_string(i)); }
  JsonWriter& value(std::size_t i) { return raw(std::to_string(i)); }
  JsonWriter& value(double d) {
    if (!std::isfinite(d)) return raw("null");
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits_, d);
    return raw(buf);
  }
  JsonWriter& null() { return raw("null"); }
  template <class T>
  JsonWriter& field(const std::string& k, const T& v) {
    key(k);
    return value(v);
  }
  JsonWriter& field_array(const std::string& k, const std::vector<double>& v) {
    key(k);
    begin_array();
    for (double d : v) value(d);
    return end_array();
  }
  const std::string& str() const { return out_; }

  static std::string quote(const std::string& s) {
    std::string q = "\"";
    for (char c : s) {
      switch (c) {
        case '"':
          q += "\\\"";
          break;
        case '\\':
          q += "\\\\";
          break;
        case '\n':
          q += "\\n";
          break;
        case '\t':
          q += "\\t";
          break;
        case '\r':
          q += "\\r";
          break;
        default:
          if (static_cast<unsigned char>(c) < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            q += buf;
          } else {
            q += c;
          }
      }
    }
    return q + "\"";
  }

 private:
  JsonWriter& open(char c) {
    raw(std::string(1, c));
    first_.push_back(true);
    return *this;
  }
  JsonWriter& close(char c) {
    const bool empty = first_.back();
    first_.pop_back();
    if (!empty) newline();
    out_ += c;
    return *this;
  }
  JsonWriter& raw(const std::string& s) {
    if (!after_key_) separate();
    after_key_ = false;
    out_ += s;
    return *this;
  }
  void separate() {
    if (first_.empty()) return;
    if (!first_.back()) out_ += ',';
    first_.back() = false;
    newline();
  }
  void newline() {
    if (indent_ <= 0) return;
    out_ += '\n';
    out_.append(first_.size() * indent_, ' ');
  }

  std::string out_;
  std::vector<bool> first_;
  int indent_;
  int digits_;
  bool after_key_ = false;
};

}  // namespace windplan
