#pragma once
// Progress of `windplan run` on stderr.
//
// Not a terminal (a log file, a pipe, the tests): one line per finished stage, as
//   windplan run: helices  done in 0.12 s
// On a terminal the same lines stay, and the stage under way is shown on the line below them,
// redrawn in place ("\r" and erase-line) every 0.2 s from a ticker thread: its name, its number
// among the stages so far and the seconds it has run; a stage that reports a count (the export:
// files written of files to write) draws a bar with the count:
//   windplan run: [stage 6] export   [##########----------]  7/13 viewer.html  0.4 s
#include <chrono>
#include <condition_variable>
#include <iosfwd>
#include <mutex>
#include <string>
#include <thread>

namespace windplan::cli {

class StageProgress {
 public:
  /// `tty`: draw the live line (the caller passes isatty(stderr)).
  StageProgress(std::ostream& err, bool tty, std::string prefix);
  ~StageProgress();
  StageProgress(const StageProgress&) = delete;
  StageProgress& operator=(const StageProgress&) = delete;

  /// A stage starts.
  void start(const std::string& stage);
  /// The stage under way has done `done` of `total` items, the last one `what`.
  void count(int done, int total, const std::string& what);
  /// The stage under way finished after `seconds`; `extra` is appended to its line.
  void finish(const std::string& stage, double seconds, const std::string& extra = "");

  /// The live line for the given state (exposed for the tests).
  static std::string live_line(const std::string& prefix, int stage_number,
                               const std::string& stage, double seconds, int done, int total,
                               const std::string& what);

 private:
  void draw_locked();
  void tick();

  std::ostream& err_;
  bool tty_;
  std::string prefix_;
  std::mutex m_;
  std::condition_variable cv_;
  std::thread ticker_;
  bool stop_ = false;
  bool active_ = false;
  int stage_number_ = 0;
  std::string stage_, what_;
  int done_ = 0, total_ = 0;
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace windplan::cli
