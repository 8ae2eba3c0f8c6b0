#include "cli/args.h"

#include <cmath>
#include <cstdlib>

#include "geometry/base/errors.h"

namespace windplan::cli {

Args::Args(const std::vector<std::string>& argv, const std::set<std::string>& flags,
           const std::set<std::string>& options) {
  for (std::size_t i = 0; i < argv.size(); ++i) {
    std::string a = argv[i];
    if (a.size() > 1 && a[0] == '-' && !(a.size() > 1 && (std::isdigit(a[1]) || a[1] == '.'))) {
      std::string v;
      bool inline_value = false;
      const auto eq = a.find('=');
      if (a.rfind("--", 0) == 0 && eq != std::string::npos) {
        v = a.substr(eq + 1);
        a = a.substr(0, eq);
        inline_value = true;
      }
      if (flags.count(a)) {
        if (inline_value) throw UsageError("option " + a + " takes no value");
        flags_.insert(a);
      } else if (options.count(a)) {
        if (!inline_value) {
          if (i + 1 >= argv.size()) throw UsageError("option " + a + " needs a value");
          v = argv[++i];
        }
        values_[a] = v;
      } else {
        throw UsageError("unknown option '" + a + "' (see --help)");
      }
    } else {
      positional_.push_back(a);
    }
  }
}

std::string Args::value(const std::string& name, const std::string& fallback) const {
  const auto it = values_.find(name);
  return it == values_.end() ? fallback : it->second;
}

double Args::number(const std::string& name, double fallback) const {
  const auto it = values_.find(name);
  if (it == values_.end()) return fallback;
  char* end = nullptr;
  const double d = std::strtod(it->second.c_str(), &end);
  if (end == it->second.c_str() || *end != '\0' || !std::isfinite(d)) {
    throw UsageError("option " + name + " expects a number, got '" + it->second + "'");
  }
  return d;
}

void Args::expect_positional(std::size_t n, const std::string& what) const {
  if (positional_.size() != n) {
    throw UsageError("expected " + what + " (got " + std::to_string(positional_.size()) +
                     " positional argument" + (positional_.size() == 1 ? "" : "s") + ")");
  }
}

}  // namespace windplan::cli
