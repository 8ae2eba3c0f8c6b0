#include "planner/job/config_node.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>
#include <utility>

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>

#include "geometry/base/atomic_file.h"
#include "geometry/base/input_file.h"

namespace windplan {

namespace {

const char* type_name(bool*) { return "a boolean (true/false)"; }
const char* type_name(int*) { return "an integer"; }
const char* type_name(double*) { return "a number"; }
const char* type_name(std::string*) { return "a string"; }

template <class T>
bool decode_scalar(const YAML::Node& n, T* out) {
  if (!n.IsScalar()) return false;
  try {
    *out = n.as<T>();
  } catch (const YAML::Exception&) {
    return false;
  }
  if constexpr (std::is_same_v<T, double>) {
    if (!std::isfinite(*out)) return false;
  }
  return true;
}

// Levenshtein distance, for "is 'lenght' a misspelling of 'length'?".
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

const char* node_kind(const YAML::Node& n) {
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a map";
  if (n.IsNull()) return "empty";
  return "not a plain name";
}

// yaml-cpp keeps the first of two equal keys without a word, and accepts any node as a key; both
// are errors here, checked once over the whole document so that no later reader meets them.
void check_keys(const YAML::Node& n, const std::string& file, const std::string& path, int depth) {
  constexpr int kMaxDepth = 64;
  if (depth > kMaxDepth) {
    throw ConfigError(file + ":" + std::to_string(n.Mark().line + 1) +
                      ": the YAML is nested more than " + std::to_string(kMaxDepth) +
                      " levels deep (a job file has at most 5)");
  }
  if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i) {
      check_keys(n[i], file, path + "[" + std::to_string(i) + "]", depth + 1);
    }
    return;
  }
  if (!n.IsMap()) return;
  std::unordered_map<std::string, int> seen;  // key -> line (linear: 100K keys took 32 s)
  for (auto it = n.begin(); it != n.end(); ++it) {
    const int line = it->first.Mark().line + 1;
    if (!it->first.IsScalar()) {
      throw ConfigError(file + ":" + std::to_string(line) + ": a key " +
                        (path.empty() ? std::string() : "in '" + path + "' ") + "is " +
                        node_kind(it->first) + "; keys must be plain names (key: value)");
    }
    const std::string k = it->first.Scalar();
    const std::string full = path.empty() ? k : path + "." + k;
    const auto [prev, fresh] = seen.emplace(k, line);
    if (!fresh) {
      throw ConfigError(file + ":" + std::to_string(line) + ": duplicate key '" + full +
                        "' (first given on line " + std::to_string(prev->second) +
                        "); keep only one");
    }
    check_keys(it->second, file, full, depth + 1);
  }
}

// The document as the parser's events, before any tree is built (issue 28): one document
// only, no tags, and the number of values it holds with every alias expanded (a 1 KB "billion
// laughs" file of nested aliases expands to 10^9) bounded by kMaxValues. Aliases are counted,
// never walked: linear in the text.
class ShapeCheck : public YAML::EventHandler {
 public:
  static constexpr std::uint64_t kMaxValues = 1000000;
  explicit ShapeCheck(const std::string& file) : file_(file) {}
  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& m, YAML::anchor_t a) override { value(m, a, 1); }
  void OnAlias(const YAML::Mark& m, YAML::anchor_t a) override {
    value(m, 0, a < sizes_.size() ? sizes_[a] : 1);
  }
  void OnScalar(const YAML::Mark& m, const std::string& tag, YAML::anchor_t a,
                const std::string&) override {
    check_tag(m, tag);
    value(m, a, 1);
  }
  void OnSequenceStart(const YAML::Mark& m, const std::string& tag, YAML::anchor_t a,
                       YAML::EmitterStyle::value) override {
    start(m, tag, a);
  }
  void OnSequenceEnd() override { end(); }
  void OnMapStart(const YAML::Mark& m, const std::string& tag, YAML::anchor_t a,
                  YAML::EmitterStyle::value) override {
    start(m, tag, a);
  }
  void OnMapEnd() override { end(); }

 private:
  void check_tag(const YAML::Mark& m, const std::string& tag) {
    if (tag.empty() || tag == "?" || tag == "!") return;
    const std::string core = "tag:yaml.org,2002:";
    const std::string shown =
        tag.compare(0, core.size(), core) == 0 ? "!!" + tag.substr(core.size()) : tag;
    throw ConfigError(file_ + ":" + std::to_string(m.line + 1) + ": a YAML tag ('" + shown +
                      "') is not used in a job file; remove it and give the plain value");
  }
  void value(const YAML::Mark& m, YAML::anchor_t a, std::uint64_t n) {
    count_ += n;
    if (count_ > kMaxValues) {
      throw ConfigError(file_ + ":" + std::to_string(m.line + 1) + ": the job holds more than " +
                        std::to_string(kMaxValues) +
                        " values once its aliases (*name) are expanded (a job file has a few "
                        "hundred); repeated aliases of aliases are refused");
    }
    if (a > 0) {
      if (sizes_.size() <= a) sizes_.resize(a + 1, 1);
      sizes_[a] = n;
    }
  }
  void start(const YAML::Mark& m, const std::string& tag, YAML::anchor_t a) {
    check_tag(m, tag);
    value(m, 0, 1);
    open_.push_back({a, count_});
  }
  void end() {
    const auto [a, at] = open_.back();
    open_.pop_back();
    if (a > 0) {
      if (sizes_.size() <= a) sizes_.resize(a + 1, 1);
      sizes_[a] = count_ - at + 1;
    }
  }
  std::string file_;
  std::uint64_t count_ = 0;
  std::vector<std::uint64_t> sizes_;  // by anchor id: values in the anchored node
  std::vector<std::pair<YAML::anchor_t, std::uint64_t>> open_;
};

// A second document ("---" then more) was ignored by YAML::Load: refused here.
class SecondDocument : public YAML::EventHandler {
 public:
  int line = 0;
  void OnDocumentStart(const YAML::Mark& m) override {
    if (line == 0) line = m.line + 1;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

// yaml-cpp's messages in the job writer's words, with the cause when it is a common one.
std::string plain_yaml_error(const std::string& text, int line, const std::string& msg) {
  std::string row;
  {
    std::istringstream in(text);
    for (int i = 0; i <= line && std::getline(in, row);) ++i;
  }
  if (row.find('\t') != std::string::npos) {
    return "a tab character; YAML indents with spaces only (replace the tab by spaces)";
  }
  if (row.size() > 1024) {
    return "a line of " + std::to_string(row.size()) +
           " characters, too long for a key (a key is a short name, at most 1024 characters)";
  }
  return "YAML syntax error (" + msg + "); check the indentation, colons and brackets";
}

}  // namespace

ConfigNode::ConfigNode(YAML::Node node, std::string file, std::string path)
    : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {
  if (present() && !node_.IsMap()) {
    throw ConfigError(where() + ": '" + (path_.empty() ? std::string("(root)") : path_) +
                      "' must be a map of key: value");
  }
}

ConfigNode ConfigNode::load_file(const std::filesystem::path& file, const std::string& what) {
  const bool vowel = !what.empty() && std::string("aeiou").find(what[0]) != std::string::npos;
  const std::string text =
      read_input_file(file, kJobFileCap, (vowel ? "an " : "a ") + what + " (YAML)");
  return load_string(text, file.string(), what);
}

ConfigNode ConfigNode::load_string(const std::string& text, const std::string& file,
                                   const std::string& what) {
  YAML::Node root;
  try {
    // First the events: one document, no tags, aliases bounded; then the tree.
    std::istringstream in(text);
    YAML::Parser parser(in);
    ShapeCheck shape(file);
    parser.HandleNextDocument(shape);
    SecondDocument second;
    if (parser.HandleNextDocument(second)) {
      throw ConfigError(file + ":" + std::to_string(second.line) +
                        ": a second YAML document ('---' starts one); a job file is one "
                        "document: remove the '---' and what follows, or put it in its own file");
    }
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(file + ":" + std::to_string(e.mark.line + 1) + ": " +
                      plain_yaml_error(text, e.mark.line, e.msg));
  }
  if (!root.IsDefined() || root.IsNull()) throw ConfigError(file + ": the " + what + " is empty");
  if (!root.IsMap()) {
    // (An arm profile named by mistake as a mesh said "the job file must be ...".)
    throw ConfigError(file + ": the " + what + " must be a YAML map of " +
                      (what == "job file" ? "sections" : "keys"));
  }
  check_keys(root, file, "", 0);
  return ConfigNode(root, file, "");
}

bool ConfigNode::has(const std::string& key) const {
  return present() && node_[key].IsDefined() && !node_[key].IsNull();
}

std::string ConfigNode::key_path(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

std::string ConfigNode::where(const std::string& key) const {
  YAML::Mark m = node_.Mark();
  if (!key.empty() && present()) {
    for (auto it = node_.begin(); it != node_.end(); ++it) {
      if (it->first.IsScalar() && it->first.Scalar() == key) {
        m = it->first.Mark();
        break;
      }
    }
  }
  if (m.is_null() || m.line < 0) return file_;
  return file_ + ":" + std::to_string(m.line + 1);
}

void ConfigNode::fail(const std::string& key, const std::string& message) const {
  throw ConfigError(where(key) + ": key '" + key_path(key) + "': " + message);
}

void ConfigNode::fail_here(const std::string& message) const {
  throw ConfigError(where() + ": section '" + (path_.empty() ? std::string("(root)") : path_) +
                    "': " + message);
}

template <class T>
bool ConfigNode::get(const std::string& key, T* out) {
  used_.insert(key);
  if (!has(key)) return false;
  const YAML::Node n = node_[key];
  if constexpr (std::is_same_v<T, std::vector<double>> ||
                std::is_same_v<T, std::vector<std::string>>) {
    using E = typename T::value_type;
    if (!n.IsSequence()) fail(key, "expected a list");
    T v;
    for (std::size_t i = 0; i < n.size(); ++i) {
      E e{};
      if (!decode_scalar(n[i], &e)) {
        fail(key, "element " + std::to_string(i) + " must be " + type_name(&e));
      }
      v.push_back(e);
    }
    *out = std::move(v);
  } else if constexpr (std::is_same_v<T, std::array<double, 3>> ||
                       std::is_same_v<T, std::array<double, 2>>) {
    constexpr std::size_t N = std::tuple_size<T>::value;
    if (!n.IsSequence() || n.size() != N) {
      fail(key, "expected a list of " + std::to_string(N) + " numbers");
    }
    T v{};
    for (std::size_t i = 0; i < N; ++i) {
      if (!decode_scalar(n[i], &v[i]))
        fail(key, "element " + std::to_string(i) + " is not a number");
    }
    *out = v;
  } else {
    T v{};
    if (!decode_scalar(n, &v)) fail(key, std::string("expected ") + type_name(&v));
    *out = v;
  }
  return true;
}

template <class T>
void ConfigNode::require(const std::string& key, T* out) {
  if (!has(key)) {
    used_.insert(key);
    // A key nobody has read that is spelt like the missing one is most likely the user's typo:
    // name both, so that the fix is one edit.
    std::string typo;
    if (present()) {
      for (auto it = node_.begin(); it != node_.end(); ++it) {
        if (!it->first.IsScalar()) continue;
        const std::string& k = it->first.Scalar();
        if (used_.count(k) || edit_distance(k, key) > std::max<std::size_t>(2, key.size() / 3)) {
          continue;
        }
        typo = "; unknown key '" + key_path(k) + "' on line " +
               std::to_string(it->first.Mark().line + 1) + " looks like a misspelling of it";
        break;
      }
    }
    fail_here("missing required key '" + key_path(key) + "'" + typo);
  }
  get(key, out);
}

template bool ConfigNode::get<bool>(const std::string&, bool*);
template bool ConfigNode::get<int>(const std::string&, int*);
template bool ConfigNode::get<double>(const std::string&, double*);
template bool ConfigNode::get<std::string>(const std::string&, std::string*);
template bool ConfigNode::get<std::vector<double>>(const std::string&, std::vector<double>*);
template bool ConfigNode::get<std::vector<std::string>>(const std::string&,
                                                        std::vector<std::string>*);
template bool ConfigNode::get<std::array<double, 3>>(const std::string&, std::array<double, 3>*);
template bool ConfigNode::get<std::array<double, 2>>(const std::string&, std::array<double, 2>*);
template void ConfigNode::require<bool>(const std::string&, bool*);
template void ConfigNode::require<int>(const std::string&, int*);
template void ConfigNode::require<double>(const std::string&, double*);
template void ConfigNode::require<std::string>(const std::string&, std::string*);
template void ConfigNode::require<std::vector<double>>(const std::string&, std::vector<double>*);
template void ConfigNode::require<std::array<double, 3>>(const std::string&,
                                                         std::array<double, 3>*);

bool ConfigNode::get_choice(const std::string& key, const std::vector<std::string>& choices,
                            std::string* out) {
  std::string v;
  if (!get(key, &v)) return false;
  for (const std::string& c : choices) {
    if (c == v) {
      *out = v;
      return true;
    }
  }
  std::string list;
  for (const std::string& c : choices) list += (list.empty() ? "" : ", ") + c;
  fail(key, "'" + v + "' is not one of: " + list);
}

bool ConfigNode::is_map(const std::string& key) const { return has(key) && node_[key].IsMap(); }

ConfigNode ConfigNode::section(const std::string& key) {
  used_.insert(key);
  if (!has(key)) return ConfigNode(YAML::Node(), file_, key_path(key));
  const YAML::Node n = node_[key];
  if (!n.IsMap()) fail(key, "expected a map of key: value");
  return ConfigNode(n, file_, key_path(key));
}

std::vector<ConfigNode> ConfigNode::list(const std::string& key) {
  used_.insert(key);
  std::vector<ConfigNode> out;
  if (!has(key)) return out;
  const YAML::Node n = node_[key];
  if (!n.IsSequence()) fail(key, "expected a list");
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (!n[i].IsMap()) fail(key, "element " + std::to_string(i) + " must be a map");
    out.emplace_back(n[i], file_, key_path(key) + "[" + std::to_string(i) + "]");
  }
  return out;
}

void ConfigNode::finish() const {
  if (!present()) return;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const std::string k = it->first.Scalar();
    if (!used_.count(k)) {
      std::string allowed;
      for (const std::string& u : used_) allowed += (allowed.empty() ? "" : ", ") + u;
      const YAML::Mark m = it->first.Mark();
      throw ConfigError(file_ + ":" + std::to_string(m.line + 1) + ": unknown key '" + key_path(k) +
                        "'" + (allowed.empty() ? "" : " (known: " + allowed + ")"));
    }
  }
}

}  // namespace windplan
