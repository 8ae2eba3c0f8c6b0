// The progress lines of `windplan run` (cli/progress.h): one line per stage off a terminal, the
// same lines plus a live line redrawn in place on one, the export's bar with its count.
#include "cli/progress.h"

#include <sstream>

#include <gtest/gtest.h>

namespace windplan::cli {
namespace {

TEST(StageProgress, OneLinePerStageOffATerminal) {
  std::ostringstream err;
  {
    StageProgress p(err, false, "windplan run");
    p.start("mandrel");
    p.finish("mandrel", 0.5);
    p.start("export");
    p.count(3, 12, "axes.csv");
    p.finish("export", 1.25, " (12 files in out)");
  }
  EXPECT_EQ(err.str(),
            "windplan run: mandrel  done in 0.50 s\n"
            "windplan run: export   done in 1.25 s (12 files in out)\n");
}

TEST(StageProgress, LiveLineWithBarAndCount) {
  EXPECT_EQ(StageProgress::live_line("windplan run", 6, "export", 0.4, 7, 14, "viewer.html"),
            "windplan run: [stage 6] export   [##########----------] 7/14 viewer.html 0.4 s");
  EXPECT_EQ(StageProgress::live_line("windplan run", 3, "helices", 2.0, 0, 0, ""),
            "windplan run: [stage 3] helices  2.0 s");
  EXPECT_EQ(StageProgress::live_line("p", 1, "x", 0.0, 14, 14, ""),
            "p: [stage 1] x        [####################] 14/14 0.0 s");
}

TEST(StageProgress, OnATerminalTheLiveLineIsErasedBeforeEachFinishedLine) {
  std::ostringstream err;
  {
    StageProgress p(err, true, "windplan run");
    p.start("export");
    p.count(1, 2, "a.csv");
    p.finish("export", 0.25);
  }
  const std::string s = err.str();
  EXPECT_NE(s.find("\r\033[Kwindplan run: [stage 1] export   [##########----------] 1/2 a.csv"),
            std::string::npos);
  EXPECT_NE(s.find("\r\033[Kwindplan run: export   done in 0.25 s\n"), std::string::npos);
  EXPECT_EQ(s.back(), '\n');
}

}  // namespace
}  // namespace windplan::cli
