#pragma once
// Strict decoding of YAML job sections (house style rule 13). A ConfigNode wraps one YAML map and
// remembers which keys were read; finish() rejects any key nobody read, so a typo is an error
// with the file, line and key named instead of a silently ignored setting.
//
// Every stage decodes its own section into its Options struct:
//   ConfigNode n = root.section("winding");
//   n.get("turns", &opts.turns);        // optional: keeps the in-class default when absent
//   n.require("file", &opts.file);      // mandatory
//   n.finish();                          // unknown keys -> ConfigError
//   n.check(opts);                       // calls opts.is_valid(&why) -> ConfigError
#include <array>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "geometry/base/errors.h"

namespace windplan {

class ConfigNode {
 public:
  /// \param node a YAML map (or a null node for an absent section)
  /// \param file the job file, for messages
  /// \param path the dotted key path of this node ("" for the root), for messages
  ConfigNode(YAML::Node node, std::string file, std::string path);

  /// Parses a job file. \throw IoError if missing, ConfigError on a YAML syntax error.
  /// `what` names the file in messages ("job file", "arm profile", ...).
  static ConfigNode load_file(const std::filesystem::path& file,
                              const std::string& what = "job file");
  /// Parses YAML text (tests); `file` names it in messages.
  static ConfigNode load_string(const std::string& text, const std::string& file,
                                const std::string& what = "job file");

  bool present() const { return node_.IsDefined() && !node_.IsNull(); }
  bool has(const std::string& key) const;
  /// The key is present and its value is a map (e.g. a key that takes a word or a map).
  bool is_map(const std::string& key) const;

  /// Reads an optional scalar/list key; leaves *out unchanged when absent.
  /// Supported T: bool, int, double, std::string, std::vector<double>, std::array<double, N>,
  /// std::vector<std::string>.
  template <class T>
  bool get(const std::string& key, T* out);
  /// Like get() but the key must be present.
  template <class T>
  void require(const std::string& key, T* out);
  /// Reads a string key that must be one of `choices`.
  bool get_choice(const std::string& key, const std::vector<std::string>& choices,
                  std::string* out);

  /// A nested map (absent -> a node with present() == false). Marks the key as used.
  ConfigNode section(const std::string& key);
  /// A nested list of maps. Marks the key as used.
  std::vector<ConfigNode> list(const std::string& key);

  /// Throws ConfigError for the first key that was never read.
  void finish() const;

  /// Calls opts.is_valid(&why) and throws ConfigError naming this section if it fails.
  template <class Options>
  void check(const Options& opts) const {
    std::string why;
    if (!opts.is_valid(&why)) fail_here(why);
  }

  [[noreturn]] void fail(const std::string& key, const std::string& message) const;
  [[noreturn]] void fail_here(const std::string& message) const;

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  /// "file:line" of this node (or of key within it).
  std::string where(const std::string& key = "") const;
  const YAML::Node& yaml() const { return node_; }

 private:
  std::string key_path(const std::string& key) const;
  YAML::Node node_;
  std::string file_;
  std::string path_;
  std::set<std::string> used_;
};

}  // namespace windplan
