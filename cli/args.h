#pragma once
// A small command-line parser for the windplan subcommands: positional arguments plus
// "--flag" and "--option value" (or "--option=value"). Unknown flags are usage errors (exit 2).
#include <map>
#include <set>
#include <string>
#include <vector>

namespace windplan::cli {

class Args {
 public:
  /// \param argv the subcommand's arguments (after the subcommand name)
  /// \param flags options that take no value (e.g. "--json")
  /// \param options options that take one value (e.g. "-o", "--out")
  /// \throw UsageError for an unknown option or a missing value
  Args(const std::vector<std::string>& argv, const std::set<std::string>& flags,
       const std::set<std::string>& options);

  bool flag(const std::string& name) const { return flags_.count(name) > 0; }
  bool has(const std::string& name) const { return values_.count(name) > 0; }
  std::string value(const std::string& name, const std::string& fallback = "") const;
  /// Parses the option as a number. \throw UsageError when it is not one.
  double number(const std::string& name, double fallback) const;
  const std::vector<std::string>& positional() const { return positional_; }
  /// Exactly n positional arguments or a UsageError naming `what`.
  void expect_positional(std::size_t n, const std::string& what) const;

 private:
  std::set<std::string> flags_;
  std::map<std::string, std::string> values_;
  std::vector<std::string> positional_;
};

}  // namespace windplan::cli
