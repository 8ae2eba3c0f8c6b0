#include "cli/progress.h"

#include <cstdio>
#include <ostream>

namespace windplan::cli {

StageProgress::StageProgress(std::ostream& err, bool tty, std::string prefix)
    : err_(err), tty_(tty), prefix_(std::move(prefix)) {
  if (tty_) ticker_ = std::thread([this] { tick(); });
}

StageProgress::~StageProgress() {
  if (!tty_) return;
  {
    std::lock_guard<std::mutex> lock(m_);
    stop_ = true;
    if (active_) err_ << "\r\033[K" << std::flush;
  }
  cv_.notify_all();
  ticker_.join();
}

std::string StageProgress::live_line(const std::string& prefix, int stage_number,
                                     const std::string& stage, double seconds, int done, int total,
                                     const std::string& what) {
  char head[160];
  std::snprintf(head, sizeof head, "%s: [stage %d] %-8s ", prefix.c_str(), stage_number,
                stage.c_str());
  std::string s = head;
  if (total > 0) {
    const int width = 20;
    const int filled = static_cast<int>(static_cast<long>(width) * done / total);
    s += "[" + std::string(filled, '#') + std::string(width - filled, '-') + "] ";
    char cnt[64];
    std::snprintf(cnt, sizeof cnt, "%d/%d ", done, total);
    s += cnt;
    if (!what.empty()) s += what + " ";
  }
  char t[32];
  std::snprintf(t, sizeof t, "%.1f s", seconds);
  return s + t;
}

void StageProgress::draw_locked() {
  if (!tty_ || !active_) return;
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  err_ << "\r\033[K" << live_line(prefix_, stage_number_, stage_, secs, done_, total_, what_)
       << std::flush;
}

void StageProgress::tick() {
  std::unique_lock<std::mutex> lock(m_);
  while (!stop_) {
    cv_.wait_for(lock, std::chrono::milliseconds(200));
    if (!stop_) draw_locked();
  }
}

void StageProgress::start(const std::string& stage) {
  std::lock_guard<std::mutex> lock(m_);
  ++stage_number_;
  stage_ = stage;
  what_.clear();
  done_ = total_ = 0;
  active_ = true;
  t0_ = std::chrono::steady_clock::now();
  draw_locked();
}

void StageProgress::count(int done, int total, const std::string& what) {
  std::lock_guard<std::mutex> lock(m_);
  done_ = done;
  total_ = total;
  what_ = what;
  draw_locked();
}

void StageProgress::finish(const std::string& stage, double seconds, const std::string& extra) {
  std::lock_guard<std::mutex> lock(m_);
  if (tty_ && active_) err_ << "\r\033[K";
  active_ = false;
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s: %-8s done in %.2f s", prefix_.c_str(), stage.c_str(),
                seconds);
  err_ << buf << extra << "\n" << std::flush;
}

}  // namespace windplan::cli
