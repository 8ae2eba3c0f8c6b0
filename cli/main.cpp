// windplan: the command-line tool. Exit codes: 0 ok, 1 bad input (a one-line message naming the
// file, key or element), 2 usage error, 3 internal error. No stack traces for user errors.
#include <cstring>
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "geometry/base/errors.h"
#include "geometry/base/parallel.h"
#include "windplan_version.h"

namespace {

// A message may quote the user's file (a malformed OFF line, a YAML scalar): control bytes and
// bytes that are not UTF-8 are shown as \xNN, so that binary garbage never reaches the terminal
// raw (escape sequences can rewrite it).
std::string printable(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c == '\t' || (c >= 0x20 && c < 0x7f)) {
      out += static_cast<char>(c);
      ++i;
      continue;
    }
    // A well-formed UTF-8 sequence of 2-4 bytes (no overlong 2-byte forms) passes as is.
    const int n = c >= 0xc2 && c <= 0xdf   ? 2
                  : c >= 0xe0 && c <= 0xef ? 3
                  : c >= 0xf0 && c <= 0xf4 ? 4
                                           : 0;
    bool ok = n > 0 && i + n <= s.size();
    for (int k = 1; ok && k < n; ++k) ok = (static_cast<unsigned char>(s[i + k]) & 0xc0) == 0x80;
    if (ok) {
      out.append(s, i, n);
      i += n;
    } else {
      static const char* digits = "0123456789abcdef";
      out += "\\x";
      out += digits[c >> 4];
      out += digits[c & 15];
      ++i;
    }
  }
  return out;
}

void print_help() {
  std::cout << "windplan " << WINDPLAN_VERSION
            << ": toolpath planner for filament winding\n\n"
               "usage: windplan <command> [options]\n"
               "       windplan --help | --version\n\n"
               "commands:\n";
  for (const auto& c : windplan::cli::commands()) {
    std::cout << "  " << c.name
              << std::string(12 - std::min<std::size_t>(11, std::strlen(c.name)), ' ') << c.summary
              << "\n";
  }
  std::cout << "\n'windplan <command> --help' describes a command.\n"
               "Every command takes --threads N: at most N threads (default: all cores); the\n"
               "files written are the same whatever N is.\n"
               "Exit codes: 0 ok, 1 bad input, 2 usage error, 3 internal error.\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::ios::sync_with_stdio(false);
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) {
    print_help();
    return 2;
  }
  if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    print_help();
    return 0;
  }
  if (args[0] == "--version" || args[0] == "-V") {
    std::cout << "windplan " << WINDPLAN_VERSION << "\n";
    return 0;
  }
  for (const auto& c : windplan::cli::commands()) {
    if (args[0] != c.name) continue;
    std::vector<std::string> rest(args.begin() + 1, args.end());
    for (const auto& a : rest) {
      if (a == "--help" || a == "-h") {
        std::cout << c.help;
        return 0;
      }
    }
    // --threads N, common to every command: a process-wide limit (geometry/base/parallel.h).
    std::unique_ptr<windplan::ThreadLimit> limit;
    for (std::size_t i = 0; i < rest.size(); ++i) {
      if (rest[i] != "--threads") continue;
      char* end = nullptr;
      const long n = i + 1 < rest.size() ? std::strtol(rest[i + 1].c_str(), &end, 10) : 0;
      if (i + 1 >= rest.size() || end == rest[i + 1].c_str() || *end != '\0' || n < 1 || n > 4096) {
        // (100000 was refused as "below 1": the message names both bounds.)
        std::cerr << "windplan " << c.name << ": --threads expects an integer from 1 to 4096"
                  << (i + 1 < rest.size() ? ", got '" + printable(rest[i + 1]) + "'"
                                          : std::string())
                  << (n > 4096 ? " (more threads than any machine runs at once)" : "") << "\n"
                  << "run 'windplan " << c.name << " --help' for usage\n";
        return 2;
      }
      limit = std::make_unique<windplan::ThreadLimit>(static_cast<int>(n));
      rest.erase(rest.begin() + static_cast<long>(i), rest.begin() + static_cast<long>(i) + 2);
      --i;
    }
    try {
      return c.run(rest);
    } catch (const windplan::UsageError& e) {
      std::cerr << "windplan " << c.name << ": " << printable(e.what()) << "\n"
                << "run 'windplan " << c.name << " --help' for usage\n";
      return 2;
    } catch (const windplan::InputError& e) {
      std::cerr << "windplan " << c.name << ": error: " << printable(e.what()) << "\n";
      return 1;
    } catch (const std::bad_alloc&) {
      std::cerr << "windplan " << c.name << ": error: out of memory\n";
      return 1;
    } catch (const std::exception& e) {
      std::cerr << "windplan " << c.name << ": internal error: " << printable(e.what()) << "\n";
      return 3;
    }
  }
  std::cerr << "windplan: unknown command '" << printable(args[0]) << "' (see windplan --help)\n";
  return 2;
}
