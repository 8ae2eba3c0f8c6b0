// geometry/cad/occt_signals.h: the scope takes the fault signals only and gives every handler
// back; the message names the signal. (The fault itself, caught from OCCT's reader: the truncated
// IGES test in cad_import_test.cpp.)
#include "geometry/cad/occt_signals.h"

#include <gtest/gtest.h>

#include <csignal>

namespace windplan {
namespace {

void my_handler(int) {}

void (*handler_of(int s))(int) {
  struct sigaction sa {};
  ::sigaction(s, nullptr, &sa);
  return sa.sa_handler;
}

TEST(OcctSignals, OnlyTheFaultSignalsAreTakenAndAllComeBack) {
  struct sigaction mine {
  }, old_int{}, old_segv{};
  mine.sa_handler = my_handler;
  sigemptyset(&mine.sa_mask);
  ::sigaction(SIGINT, &mine, &old_int);
  ::sigaction(SIGSEGV, &mine, &old_segv);
  {
    OcctSignalScope outer;
    EXPECT_EQ(handler_of(SIGINT), my_handler);  // the output folder's clean-up stays
    EXPECT_NE(handler_of(SIGSEGV), my_handler);
    {
      OcctSignalScope inner;
      EXPECT_NE(handler_of(SIGSEGV), my_handler);
    }
    EXPECT_NE(handler_of(SIGSEGV), my_handler);  // still inside the outer scope
  }
  EXPECT_EQ(handler_of(SIGSEGV), my_handler);
  EXPECT_EQ(handler_of(SIGINT), my_handler);
  ::sigaction(SIGINT, &old_int, nullptr);
  ::sigaction(SIGSEGV, &old_segv, nullptr);
}

TEST(OcctSignals, TheMessageNamesTheSignalAndTheCause) {
  EXPECT_EQ(occt_failure_text("SIGSEGV 'segmentation violation' detected. Address 8"),
            "it crashed OpenCASCADE (SIGSEGV, a memory access fault): the file is damaged or "
            "truncated");
  EXPECT_EQ(occt_failure_text("Standard_OutOfRange"), "OpenCASCADE: Standard_OutOfRange");
}

}  // namespace
}  // namespace windplan
