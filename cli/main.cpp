// windplan: the command-line tool. Exit codes: 0 ok, 1 bad input (a one-line message naming the
// file, key or element), 2 usage error, 3 internal error. No stack traces for user errors.
#include <cstring>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "geometry/errors.h"
#include "geometry/parallel.h"
#include "windplan_version.h"

namespace {

void print_help() {
  std::cout << "windplan " << WINDPLAN_VERSION
            << ": toolpath planner for filament winding\n\n"
               "usage: windplan <command> [options]\n"
               "       windplan --help | --version\n\n"
               "commands:\n";
  for (const auto& c : windplan::cli::commands()) {
    std::cout << "  " << c.name << std::string(12 - std::min<std::size_t>(11, std::strlen(c.name)), ' ')
              << c.summary << "\n";
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
    // --threads N, common to every command: a process-wide limit (geometry/parallel.h).
    std::unique_ptr<windplan::ThreadLimit> limit;
    for (std::size_t i = 0; i < rest.size(); ++i) {
      if (rest[i] != "--threads") continue;
      char* end = nullptr;
      const long n = i + 1 < rest.size() ? std::strtol(rest[i + 1].c_str(), &end, 10) : 0;
      if (i + 1 >= rest.size() || end == rest[i + 1].c_str() || *end != '\0' || n < 1 ||
          n > 4096) {
        std::cerr << "windplan " << c.name << ": --threads expects an integer >= 1"
                  << (i + 1 < rest.size() ? ", got '" + rest[i + 1] + "'" : std::string()) << "\n"
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
      std::cerr << "windplan " << c.name << ": " << e.what() << "\n"
                << "run 'windplan " << c.name << " --help' for usage\n";
      return 2;
    } catch (const windplan::InputError& e) {
      std::cerr << "windplan " << c.name << ": error: " << e.what() << "\n";
      return 1;
    } catch (const std::bad_alloc&) {
      std::cerr << "windplan " << c.name << ": error: out of memory\n";
      return 1;
    } catch (const std::exception& e) {
      std::cerr << "windplan " << c.name << ": internal error: " << e.what() << "\n";
      return 3;
    }
  }
  std::cerr << "windplan: unknown command '" << args[0] << "' (see windplan --help)\n";
  return 2;
}
