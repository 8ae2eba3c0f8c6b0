#include "geometry/cad/occt_signals.h"

#include <pthread.h>
#include <signal.h>

#include <csignal>
#include <cstdint>

#include <OSD.hxx>

namespace windplan {

namespace {

constexpr int kFaults[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL};
int g_depth = 0;
struct sigaction g_saved[NSIG];
struct sigaction g_occt[NSIG];  // OCCT's own handlers, called from fault_handler

// The alternate stack the fault handlers run on (a stack overflow leaves no room on the thread's
// own stack: issue 28's fuzz_cad SIGSEGV, a STEP TRIMMED_CURVE that is its own basis curve).
constexpr std::size_t kAltStackBytes = 1 << 20;
alignas(16) char g_alt_stack[kAltStackBytes];
bool g_alt_installed = false;
stack_t g_alt_saved{};

// The thread's stack, to tell a stack overflow from another fault.
std::uintptr_t g_stack_lo = 0;
std::uintptr_t g_stack_hi = 0;
volatile sig_atomic_t g_overflow = 0;

bool is_fault(int s) {
  for (int f : kFaults) {
    if (f == s) return true;
  }
  return false;
}

void record_stack_bounds() {
  g_stack_lo = g_stack_hi = 0;
  pthread_attr_t attr;
  if (::pthread_getattr_np(::pthread_self(), &attr) != 0) return;
  void* addr = nullptr;
  std::size_t size = 0;
  if (::pthread_attr_getstack(&attr, &addr, &size) == 0) {
    g_stack_lo = reinterpret_cast<std::uintptr_t>(addr);
    g_stack_hi = g_stack_lo + size;
  }
  ::pthread_attr_destroy(&attr);
}

// Notes whether the fault is at the end of the thread's stack, then hands over to OCCT's handler
// (which jumps back to the OCC_CATCH_SIGNALS point as a Standard_Failure).
void fault_handler(int s, siginfo_t* info, void* context) {
  const auto at = reinterpret_cast<std::uintptr_t>(info ? info->si_addr : nullptr);
  constexpr std::uintptr_t kGuard = 1 << 16;
  g_overflow =
      (s == SIGSEGV && g_stack_lo != 0 && at + kGuard >= g_stack_lo && at < g_stack_lo + kGuard)
          ? 1
          : 0;
  const struct sigaction& occt = g_occt[s];
  if (occt.sa_flags & SA_SIGINFO) {
    if (occt.sa_sigaction) occt.sa_sigaction(s, info, context);
  } else if (occt.sa_handler != SIG_DFL && occt.sa_handler != SIG_IGN && occt.sa_handler) {
    occt.sa_handler(s);
  }
  // OCCT's handler returned (it does not when a jump point is set): die with the signal.
  ::signal(s, SIG_DFL);
  ::raise(s);
}

}  // namespace

OcctSignalScope::OcctSignalScope() {
  if (g_depth++ > 0) return;
  g_overflow = 0;
  for (int s = 1; s < NSIG; ++s) ::sigaction(s, nullptr, &g_saved[s]);
  OSD::SetSignal(OSD_SignalMode_Set, Standard_False);
  // OCCT also takes SIGINT, SIGHUP, SIGQUIT...: give them back at once.
  for (int s = 1; s < NSIG; ++s) {
    if (!is_fault(s) && s != SIGKILL && s != SIGSTOP) ::sigaction(s, &g_saved[s], nullptr);
  }
  // OCCT's fault handlers run on the thread's stack: on an alternate one instead, through
  // fault_handler, so that an overflow is caught like any other fault.
  record_stack_bounds();
  stack_t current{};
  if (::sigaltstack(nullptr, &current) == 0 && !(current.ss_flags & SS_ONSTACK) &&
      ((current.ss_flags & SS_DISABLE) || current.ss_size < kAltStackBytes)) {
    stack_t mine{};
    mine.ss_sp = g_alt_stack;
    mine.ss_size = kAltStackBytes;
    g_alt_installed = ::sigaltstack(&mine, &g_alt_saved) == 0;
  }
  for (int s : kFaults) {
    ::sigaction(s, nullptr, &g_occt[s]);
    struct sigaction wrap = g_occt[s];
    wrap.sa_sigaction = fault_handler;
    wrap.sa_flags = (g_occt[s].sa_flags | SA_SIGINFO | SA_ONSTACK) & ~SA_RESETHAND;
    ::sigaction(s, &wrap, nullptr);
  }
}

OcctSignalScope::~OcctSignalScope() {
  if (--g_depth > 0) return;
  for (int s : kFaults) ::sigaction(s, &g_saved[s], nullptr);
  if (g_alt_installed) {
    ::sigaltstack(&g_alt_saved, nullptr);
    g_alt_installed = false;
  }
}

bool occt_fault_was_stack_overflow() { return g_overflow != 0; }

std::string occt_failure_text(const std::string& what) {
  static const char* const kNames[][2] = {{"SIGSEGV", "a memory access fault"},
                                          {"SIGBUS", "a bus error"},
                                          {"SIGFPE", "an arithmetic fault"},
                                          {"SIGILL", "an illegal instruction"}};
  for (const auto& n : kNames) {
    if (what.find(n[0]) != std::string::npos) {
      if (n[0] == std::string("SIGSEGV") && g_overflow) {
        return "it crashed OpenCASCADE (SIGSEGV, its recursion overflowed the stack): the file "
               "refers to itself (an entity that is its own part?) or nests too deep";
      }
      return std::string("it crashed OpenCASCADE (") + n[0] + ", " + n[1] +
             "): the file is damaged or truncated";
    }
  }
  return "OpenCASCADE: " + what;
}

}  // namespace windplan
