#include "export/files/output_set.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <system_error>

#include "geometry/base/atomic_file.h"
#include "geometry/base/errors.h"
#include "geometry/base/parallel.h"

namespace windplan {

namespace fs = std::filesystem;

namespace {

// ---- removal of the staging folder from a signal handler (async-signal-safe calls only) ----

char g_staging[4096];                     // the folder to remove on a signal
volatile std::sig_atomic_t g_active = 0;  // g_staging is set
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};
struct sigaction g_previous[4];

struct LinuxDirent64 {  // the kernel's struct linux_dirent64
  unsigned long long d_ino;
  long long d_off;
  unsigned short d_reclen;
  unsigned char d_type;
  char d_name[1];
};

// Unlinks every entry of a flat folder (the staging folder holds files only) and the folder:
// open, getdents64, unlinkat, rmdir are async-signal-safe, unlike opendir or remove_all.
void remove_flat_folder(const char* path) {
  for (int pass = 0; pass < 4; ++pass) {  // unlinking while reading may skip entries: re-read
    const int fd = ::open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    bool removed = false;
    alignas(8) char buf[4096];
    for (;;) {
      const long n = ::syscall(SYS_getdents64, fd, buf, sizeof buf);
      if (n <= 0) break;
      for (long off = 0; off < n;) {
        const LinuxDirent64* d = reinterpret_cast<const LinuxDirent64*>(buf + off);
        const char* nm = d->d_name;
        if (!(nm[0] == '.' && (nm[1] == 0 || (nm[1] == '.' && nm[2] == 0)))) {
          removed = ::unlinkat(fd, nm, 0) == 0 || removed;
        }
        off += d->d_reclen;
      }
    }
    ::close(fd);
    if (::rmdir(path) == 0 || !removed) return;
  }
}

void on_signal(int sig) {
  if (g_active) remove_flat_folder(g_staging);
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

void install_handlers(const fs::path& staging) {
  sigset_t block, old;
  sigemptyset(&block);
  for (int s : kSignals) sigaddset(&block, s);
  ::sigprocmask(SIG_BLOCK, &block, &old);
  std::snprintf(g_staging, sizeof g_staging, "%s", staging.c_str());
  g_active = staging.string().size() < sizeof g_staging;
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  for (int i = 0; i < 4; ++i) ::sigaction(kSignals[i], &sa, &g_previous[i]);
  ::sigprocmask(SIG_SETMASK, &old, nullptr);
}

void remove_handlers() {
  sigset_t block, old;
  sigemptyset(&block);
  for (int s : kSignals) sigaddset(&block, s);
  ::sigprocmask(SIG_BLOCK, &block, &old);
  g_active = 0;
  for (int i = 0; i < 4; ++i) ::sigaction(kSignals[i], &g_previous[i], nullptr);
  ::sigprocmask(SIG_SETMASK, &old, nullptr);
}

void fsync_path(const fs::path& p, bool folder) {
  const int fd = ::open(p.c_str(), (folder ? O_RDONLY | O_DIRECTORY : O_RDONLY) | O_CLOEXEC);
  if (fd < 0) throw IoError(p.string() + ": cannot open to sync: " + std::strerror(errno));
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0) throw IoError(p.string() + ": fsync failed: " + std::strerror(err));
}

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

}  // namespace

bool is_windplan_output_name(const std::string& name) {
  static const std::set<std::string> names = {
      "fibre_path.csv", "payout.csv",    "axes.csv",           "eye_pose.csv",
      "cutlines.csv",   "toolpath.ngc",  "toolpath.gcode",     "toolpath.nc",
      "mesh.ply",       "paths.ply",     "development.svg",    "report.json",
      "report.md",      "manifest.json", "axes.svg",           "viewer.html",
      "laminate.csv",   "laminate.vtu",  "layer_profiles.csv", "layer_profiles.svg"};
  if (names.count(name)) return true;
  // "<name>.tmp.<pid>": a temporary of write_file_atomically left by a killed run.
  const std::size_t t = name.rfind(".tmp.");
  if (t == std::string::npos || t + 5 == name.size()) return false;
  for (std::size_t i = t + 5; i < name.size(); ++i) {
    if (name[i] < '0' || name[i] > '9') return false;
  }
  return names.count(name.substr(0, t)) > 0;
}

OutputSet::OutputSet(const fs::path& dir) {
  fs::path d = fs::absolute(dir).lexically_normal();
  if (!d.has_filename()) d = d.parent_path();  // "out/x/" -> "out/x"
  const std::string name = d.filename().string();
  if (name.empty() || name == "." || name == ".." || d == d.root_path()) {
    throw IoError(dir.string() + ": cannot be used as an output folder");
  }
  dir_ = d;
  const fs::path parent = d.parent_path();
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw IoError(parent.string() + ": cannot create directory: " + ec.message());

  // The lock, before anything else is touched.
  const fs::path lock = parent / ("." + name + ".lock");
  lock_fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd_ < 0) {
    throw IoError(lock.string() + ": cannot create the lock file: " + std::strerror(errno));
  }
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    char pid[32] = {0};
    const ssize_t n = ::pread(lock_fd_, pid, sizeof pid - 1, 0);
    ::close(lock_fd_);
    lock_fd_ = -1;
    std::string holder = n > 0 ? std::string(pid, static_cast<std::size_t>(n)) : "";
    holder.erase(std::remove(holder.begin(), holder.end(), '\n'), holder.end());
    throw IoError(dir_.string() + ": another windplan run" +
                  (holder.empty() ? std::string() : " (pid " + holder + ")") +
                  " is writing this output folder; wait for it to finish or choose another --out");
  }
  const std::string me = std::to_string(::getpid()) + "\n";
  if (::ftruncate(lock_fd_, 0) != 0 || ::pwrite(lock_fd_, me.data(), me.size(), 0) < 0) {
    // The pid is only for the message of a refused run; the lock holds without it.
  }

  try {
    // Leftovers of runs killed by SIGKILL: no other run owns them while we hold the lock.
    for (const auto& e : fs::directory_iterator(parent, ec)) {
      const std::string n = e.path().filename().string();
      if (starts_with(n, "." + name + ".staging.") || starts_with(n, "." + name + ".old.")) {
        fs::remove_all(e.path(), ec);
      }
    }
    // Only a folder windplan wrote is replaced.
    if (fs::exists(dir_, ec)) {
      if (!fs::is_directory(dir_, ec)) {
        throw IoError(dir_.string() + ": exists and is not a folder; choose another --out");
      }
      std::set<std::string> listed;
      const fs::path manifest = dir_ / "manifest.json";
      if (fs::is_regular_file(manifest, ec)) {
        for (const std::string& f : manifest_file_names(read_text_file(manifest))) listed.insert(f);
      }
      for (const auto& e : fs::directory_iterator(dir_)) {
        const std::string n = e.path().filename().string();
        const bool file = e.is_regular_file(ec) && !e.is_symlink(ec);
        if (file && (listed.count(n) || is_windplan_output_name(n))) continue;
        throw IoError(e.path().string() + ": not written by windplan; each run replaces the " +
                      "output folder whole, so it must hold only windplan's files (remove it " +
                      "or choose another --out)");
      }
    }
    staging_ = parent / ("." + name + ".staging." + std::to_string(::getpid()));
    fs::create_directory(staging_, ec);
    if (ec) throw IoError(staging_.string() + ": cannot create directory: " + ec.message());
    install_handlers(staging_);
  } catch (...) {
    ::close(lock_fd_);
    lock_fd_ = -1;
    throw;
  }
}

OutputSet::~OutputSet() {
  if (!staging_.empty()) {
    std::error_code ec;
    fs::remove_all(staging_, ec);  // the unfinished new set, or after commit the previous one
    remove_handlers();
  }
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the lock
}

void OutputSet::commit(Manifest m, const std::vector<std::string>& order) {
  std::error_code ec;
  std::set<std::string> present;
  for (const auto& e : fs::directory_iterator(staging_)) {
    if (e.path().filename() != "manifest.json") present.insert(e.path().filename().string());
  }
  std::vector<std::string> names;  // the manifest's order: `order` first, then the rest
  for (const std::string& n : order) {
    if (present.erase(n)) names.push_back(n);
  }
  names.insert(names.end(), present.begin(), present.end());
  // The files are hashed in parallel (each entry its own slot, the order kept).
  m.files.assign(names.size(), ManifestEntry{});
  parallel_for_index(static_cast<int>(names.size()), [&](int i) {
    m.files[i] = manifest_entry(staging_ / names[i], names[i], false);
  });
  write_text_atomically(staging_ / "manifest.json", manifest_json(m));
  for (const auto& e : fs::directory_iterator(staging_)) fsync_path(e.path(), false);
  fsync_path(staging_, true);
  output_test_pause("swap");

  // The swap: after it, staging_ names the previous set (or nothing).
  const fs::path parent = dir_.parent_path();
  if (fs::exists(dir_, ec)) {
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, dir_.c_str(), RENAME_EXCHANGE) == 0) {
      // Both names exist throughout: dir is the previous set, then the new one.
    } else if (errno != EINVAL && errno != ENOSYS && errno != ENOTSUP) {
      throw IoError(dir_.string() + ": cannot swap in the new set: " + std::strerror(errno));
    } else {
      // No atomic exchange on this file system: dir is absent between the renames, never mixed.
      const fs::path old =
          parent / ("." + dir_.filename().string() + ".old." + std::to_string(::getpid()));
      fs::rename(dir_, old, ec);
      if (ec) throw IoError(dir_.string() + ": cannot move the previous set: " + ec.message());
      fs::rename(staging_, dir_, ec);
      if (ec) {
        std::error_code back;
        fs::rename(old, dir_, back);
        throw IoError(dir_.string() + ": cannot swap in the new set: " + ec.message());
      }
      fs::rename(old, staging_, ec);  // so that the clean-up below removes it
    }
  } else {
    fs::rename(staging_, dir_, ec);
    if (ec) throw IoError(dir_.string() + ": cannot move the new set in: " + ec.message());
  }
  committed_ = true;
  fsync_path(parent, true);
  fs::remove_all(staging_, ec);  // the previous set
}

void output_test_pause(const std::string& name) {
  const char* want = std::getenv("WINDPLAN_TEST_PAUSE_AFTER");
  if (want == nullptr || name != want) return;
  const std::string line = "windplan: test pause after " + name + "\n";
  if (::write(2, line.data(), line.size()) < 0) {
  }
  for (;;) ::pause();
}

}  // namespace windplan
