#include "geometry/cad/occt_signals.h"

#include <csignal>

#include <OSD.hxx>

namespace windplan {

namespace {

constexpr int kFaults[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL};
int g_depth = 0;
struct sigaction g_saved[NSIG];

bool is_fault(int s) {
  for (int f : kFaults) {
    if (f == s) return true;
  }
  return false;
}

}  // namespace

OcctSignalScope::OcctSignalScope() {
  if (g_depth++ > 0) return;
  for (int s = 1; s < NSIG; ++s) ::sigaction(s, nullptr, &g_saved[s]);
  OSD::SetSignal(OSD_SignalMode_Set, Standard_False);
  // OCCT also takes SIGINT, SIGHUP, SIGQUIT...: give them back at once.
  for (int s = 1; s < NSIG; ++s) {
    if (!is_fault(s) && s != SIGKILL && s != SIGSTOP) ::sigaction(s, &g_saved[s], nullptr);
  }
}

OcctSignalScope::~OcctSignalScope() {
  if (--g_depth > 0) return;
  for (int s : kFaults) ::sigaction(s, &g_saved[s], nullptr);
}

std::string occt_failure_text(const std::string& what) {
  static const char* const kNames[][2] = {{"SIGSEGV", "a memory access fault"},
                                          {"SIGBUS", "a bus error"},
                                          {"SIGFPE", "an arithmetic fault"},
                                          {"SIGILL", "an illegal instruction"}};
  for (const auto& n : kNames) {
    if (what.find(n[0]) != std::string::npos) {
      return std::string("it crashed OpenCASCADE (") + n[0] + ", " + n[1] +
             "): the file is damaged or truncated";
    }
  }
  return "OpenCASCADE: " + what;
}

}  // namespace windplan
