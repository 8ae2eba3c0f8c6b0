#pragma once
// OpenCASCADE's crashes as exceptions: a damaged STEP or IGES file can make OCCT's readers or
// mesher dereference garbage (issue 28: a truncated IGES file, SIGSEGV in 8 of 9 truncation
// points, the process gone and its staging folder left). Inside an OcctSignalScope, SIGSEGV,
// SIGBUS, SIGFPE and SIGILL raised while OCCT code runs under OCC_CATCH_SIGNALS (in the .cpp
// files of geometry/cad, built with OCC_CONVERT_SIGNALS as Debian's OCCT is) jump back to that
// point and are thrown as Standard_Failure (OSD_SIGSEGV, ...), which the callers turn into an
// InputError naming the file.
//
//   OcctSignalScope scope;              // OCCT's handlers for the four fault signals only
//   try { OCC_CATCH_SIGNALS  reader.ReadFile(...); } catch (const Standard_Failure& e) { ... }
//
// - Only the fault signals are taken; every other handler (the output folder's SIGINT/SIGTERM
//   clean-up, export/files/output_set.h) is left as it was. The previous handlers come back
//   when the outermost scope ends. Scopes nest; they are meant for the main thread.
// - The fault handlers run on an alternate stack (1 MB, installed for the scope when the thread
//   has none or a smaller one), so a stack overflow inside OCCT's recursive readers (a STEP
//   TRIMMED_CURVE or ORIENTED_EDGE that is its own part: fuzz_cad, issue 28) is caught like any
//   other fault instead of killing the process; occt_fault_was_stack_overflow() tells which.
// - After such a jump OCCT's state may hold leaks: the process reports the error and ends.

#include <string>

namespace windplan {

class OcctSignalScope {
 public:
  OcctSignalScope();
  ~OcctSignalScope();
  OcctSignalScope(const OcctSignalScope&) = delete;
  OcctSignalScope& operator=(const OcctSignalScope&) = delete;
};

/// Whether the last fault caught in a scope was at the end of the thread's stack (an overflow).
bool occt_fault_was_stack_overflow();

/// The message of a Standard_Failure thrown for a signal, as one line for the user: e.g.
/// "it crashed OpenCASCADE (SIGSEGV, a memory access fault): the file is damaged or truncated"
/// when `what` names a signal (for a SIGSEGV that overflowed the stack: "...its recursion
/// overflowed the stack: the file refers to itself..."), else "OpenCASCADE: <what>".
std::string occt_failure_text(const std::string& what);

}  // namespace windplan
