#include "export/files/output_set.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <system_error>

#include "export/files/sha256.h"
#include "geometry/base/atomic_file.h"
#include "geometry/base/errors.h"
#include "geometry/base/parallel.h"

namespace windplan {

namespace fs = std::filesystem;

namespace {

// ---- removal of the staging folder from a signal handler (async-signal-safe calls only) ----

char g_staging[4096];                     // the folder to remove on a signal
char g_lock[4096];                        // the lock file to remove on a signal
volatile std::sig_atomic_t g_active = 0;  // g_staging and g_lock are set
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
  if (g_active) {
    remove_flat_folder(g_staging);
    ::unlink(g_lock);  // held by this process: no other run holds this file
  }
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

void install_handlers(const fs::path& staging, const fs::path& lock) {
  sigset_t block, old;
  sigemptyset(&block);
  for (int s : kSignals) sigaddset(&block, s);
  ::sigprocmask(SIG_BLOCK, &block, &old);
  std::snprintf(g_staging, sizeof g_staging, "%s", staging.c_str());
  std::snprintf(g_lock, sizeof g_lock, "%s", lock.c_str());
  g_active = staging.string().size() < sizeof g_staging && lock.string().size() < sizeof g_lock;
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

namespace {

// A robot program of export/robot/robot_program.h: "wp_<job>.src|.dat|.mod" and its parts
// "wp_<job>_pNN.*" (the job's name as robot_program_base() writes it: letters, digits, '_').
bool is_robot_program_name(const std::string& name) {
  const std::size_t dot = name.rfind('.');
  if (name.rfind("wp_", 0) != 0 || dot == std::string::npos || dot <= 3) return false;
  const std::string ext = name.substr(dot);
  if (ext != ".src" && ext != ".dat" && ext != ".mod") return false;
  for (std::size_t i = 3; i < dot; ++i) {
    const char c = name[i];
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  }
  return true;
}

}  // namespace

bool is_windplan_output_name(const std::string& name) {
  static const std::set<std::string> names = {
      "fibre_path.csv",  "payout.csv",    "axes.csv",           "eye_pose.csv",
      "cutlines.csv",    "toolpath.ngc",  "toolpath.gcode",     "toolpath.nc",
      "mesh.ply",        "paths.ply",     "development.svg",    "report.json",
      "report.md",       "manifest.json", "axes.svg",           "viewer.html",
      "laminate.csv",    "laminate.vtu",  "layer_profiles.csv", "layer_profiles.svg",
      "stability.svg",   "joints.csv",    "joints.svg",         "model.inp",
      "model_plies.csv", "design.md"};
  if (names.count(name) || is_robot_program_name(name)) return true;
  // "<name>.tmp.<pid>": a temporary of write_file_atomically left by a killed run.
  const std::size_t t = name.rfind(".tmp.");
  if (t == std::string::npos || t + 5 == name.size()) return false;
  for (std::size_t i = t + 5; i < name.size(); ++i) {
    if (name[i] < '0' || name[i] > '9') return false;
  }
  return names.count(name.substr(0, t)) > 0;
}

namespace {

constexpr std::uintmax_t kManifestCap = 1u << 20;  // bytes: a manifest of 10^4 files is ~1 MB

std::string name_list(const std::vector<std::string>& names) {
  std::string out;
  const std::size_t shown = std::min<std::size_t>(names.size(), 8);
  for (std::size_t i = 0; i < shown; ++i) out += (i ? ", " : "") + names[i];
  if (names.size() > shown) out += " and " + std::to_string(names.size() - shown) + " more";
  return out;
}

// Removes the regular files of `folder` that windplan writes (or all `only` names when given),
// then the folder if that emptied it. Never removes anything else. Returns true if it is gone.
bool remove_windplan_files(const fs::path& folder, const std::vector<std::string>* only) {
  std::error_code ec;
  std::set<std::string> allowed;
  if (only) allowed.insert(only->begin(), only->end());
  for (const auto& e : fs::directory_iterator(folder, ec)) {
    const std::string n = e.path().filename().string();
    const bool file = e.is_regular_file(ec) && !e.is_symlink(ec);
    if (file && (only ? allowed.count(n) > 0 : is_windplan_output_name(n))) {
      std::error_code rm;
      fs::remove(e.path(), rm);
    }
  }
  return ::rmdir(folder.c_str()) == 0;
}

}  // namespace

std::vector<std::string> verify_output_folder(const fs::path& dir) {
  std::error_code ec;
  std::vector<std::string> present;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    present.push_back(e.path().filename().string());
  }
  if (ec) throw IoError(dir.string() + ": cannot list the folder: " + ec.message());
  std::sort(present.begin(), present.end());
  if (present.empty()) return {};
  std::vector<std::string> foreign;
  auto refuse = [&](const std::string& why) {
    throw IoError(dir.string() + ": holds " + std::to_string(foreign.size()) +
                  (foreign.size() == 1 ? " file" : " files") +
                  " windplan did not write: " + name_list(foreign) + " (" + why +
                  "); each run replaces the output folder whole, so it must be empty or hold "
                  "a set windplan wrote, unchanged: move them away or choose another --out");
  };
  // manifest.json: a regular file of bounded size, in windplan's layout.
  const fs::path manifest = dir / "manifest.json";
  struct stat st {};
  std::vector<ManifestEntry> listed;
  std::string why;
  if (::lstat(manifest.c_str(), &st) != 0) {
    why = "no manifest.json";
  } else if (!S_ISREG(st.st_mode)) {
    why = "manifest.json is not a regular file";
  } else if (static_cast<std::uintmax_t>(st.st_size) > kManifestCap) {
    why = "manifest.json is larger than windplan writes";
  } else if (!parse_manifest_files(read_text_file(manifest), &listed)) {
    why = "manifest.json is not one windplan wrote";
  }
  if (!why.empty()) {
    foreign = present;
    refuse(why);
  }
  std::map<std::string, const ManifestEntry*> by_name;
  for (const ManifestEntry& e : listed) by_name[e.name] = &e;
  std::vector<std::string> reasons;
  for (const std::string& n : present) {
    if (n == "manifest.json") continue;
    const auto it = by_name.find(n);
    std::string bad;
    struct stat fst {};
    if (it == by_name.end()) {
      bad = "not listed in manifest.json";
    } else if (!is_windplan_output_name(n) || n.find(".tmp.") != std::string::npos) {
      bad = "listed, but not a name windplan writes";
    } else if (::lstat((dir / n).c_str(), &fst) != 0 || !S_ISREG(fst.st_mode)) {
      bad = "not a regular file";
    } else if (static_cast<std::uintmax_t>(fst.st_size) != it->second->size ||
               sha256_file(dir / n) != it->second->sha256) {
      bad = "changed since windplan wrote it";
    }
    if (!bad.empty()) {
      foreign.push_back(n);
      if (std::find(reasons.begin(), reasons.end(), bad) == reasons.end()) reasons.push_back(bad);
    }
    if (it != by_name.end()) by_name.erase(it);
  }
  if (!foreign.empty()) {
    std::string all;
    for (const std::string& r : reasons) all += (all.empty() ? "" : "; ") + r;
    refuse(all);
  }
  if (!by_name.empty()) {
    std::vector<std::string> missing;
    for (const auto& kv : by_name) missing.push_back(kv.first);
    throw IoError(dir.string() + ": manifest.json lists " + name_list(missing) +
                  ", missing from the folder: not a complete set windplan wrote, so it is not "
                  "replaced; remove the folder or choose another --out");
  }
  std::vector<std::string> names;
  for (const ManifestEntry& e : listed) names.push_back(e.name);
  names.push_back("manifest.json");
  return names;
}

OutputSet::OutputSet(const fs::path& dir) {
  if (dir.empty()) throw IoError("--out: the output folder name is empty");
  fs::path d = fs::absolute(dir).lexically_normal();
  if (!d.has_filename()) d = d.parent_path();  // "out/x/" -> "out/x"
  const std::string name = d.filename().string();
  if (name.empty() || name == "." || name == ".." || d == d.root_path()) {
    throw IoError(dir.string() + ": cannot be used as an output folder");
  }
  dir_ = d;
  const fs::path parent = d.parent_path();

  // What --out names, checked before anything is created: a symbolic link (dangling or not) or
  // a mount point cannot be swapped by a rename, a file is not a folder.
  struct stat st {};
  if (::lstat(dir_.c_str(), &st) == 0) {
    if (S_ISLNK(st.st_mode)) {
      throw IoError(dir_.string() + ": is a symbolic link" +
                    (fs::exists(dir_) ? "" : " to nothing (dangling)") +
                    "; windplan replaces the output folder whole by renaming, so give the real "
                    "folder's path or another --out");
    }
    if (!S_ISDIR(st.st_mode)) {
      throw IoError(dir_.string() + ": exists and is not a folder; choose another --out");
    }
    struct stat pst {};
    struct statx sx {};
    const bool mount_root =
        ::statx(AT_FDCWD, dir_.c_str(), AT_SYMLINK_NOFOLLOW, STATX_BASIC_STATS, &sx) == 0 &&
        (sx.stx_attributes_mask & STATX_ATTR_MOUNT_ROOT) &&
        (sx.stx_attributes & STATX_ATTR_MOUNT_ROOT);
    if (mount_root || (::stat(parent.c_str(), &pst) == 0 && pst.st_dev != st.st_dev)) {
      throw IoError(dir_.string() + ": is a mount point; windplan replaces the output folder " +
                    "whole by renaming, which a mount point cannot be: give a folder inside it");
    }
  } else if (errno != ENOENT) {
    throw IoError(dir_.string() + ": cannot be used as an output folder: " + std::strerror(errno));
  }
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw IoError(parent.string() + ": cannot create directory: " + ec.message());

  // The lock (flock on "<parent>/.<name>.lock"). Whoever holds it removes the file when done, so
  // a lock file whose path no longer names the locked file was released: open it again.
  lock_path_ = parent / ("." + name + ".lock");
  for (int attempt = 0;; ++attempt) {
    lock_fd_ = ::open(lock_path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (lock_fd_ < 0) {
      throw IoError(lock_path_.string() + ": cannot create the lock file: " + std::strerror(errno));
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
                    " is writing this output folder; wait for it to finish or choose another " +
                    "--out");
    }
    struct stat held {
    }, named{};
    if (::fstat(lock_fd_, &held) == 0 && ::lstat(lock_path_.c_str(), &named) == 0 &&
        held.st_dev == named.st_dev && held.st_ino == named.st_ino) {
      break;
    }
    ::close(lock_fd_);  // released and removed by its holder meanwhile
    lock_fd_ = -1;
    if (attempt == 100) throw IoError(lock_path_.string() + ": cannot hold the lock file");
  }
  const std::string me = std::to_string(::getpid()) + "\n";
  if (::ftruncate(lock_fd_, 0) != 0 || ::pwrite(lock_fd_, me.data(), me.size(), 0) < 0) {
    // The pid is only for the message of a refused run; the lock holds without it.
  }

  try {
    // Leftovers of runs killed by SIGKILL: no other run owns them while we hold the lock. Only
    // windplan's own files in them are removed.
    for (const auto& e : fs::directory_iterator(parent, ec)) {
      const std::string n = e.path().filename().string();
      if ((starts_with(n, "." + name + ".staging.") || starts_with(n, "." + name + ".old.")) &&
          e.is_directory(ec) && !e.is_symlink(ec)) {
        remove_windplan_files(e.path(), nullptr);
      }
    }
    // Only a folder windplan wrote, unchanged, is replaced.
    if (fs::is_directory(dir_, ec)) verify_output_folder(dir_);
    staging_ = parent / ("." + name + ".staging." + std::to_string(::getpid()));
    if (::mkdir(staging_.c_str(), 0755) != 0) {
      const int err = errno;
      staging_.clear();
      throw IoError(parent.string() + ": cannot create the staging folder: " + std::strerror(err));
    }
    install_handlers(staging_, lock_path_);
  } catch (...) {
    release_lock();
    throw;
  }
}

void OutputSet::release_lock() {
  if (lock_fd_ < 0) return;
  ::unlink(lock_path_.c_str());  // while held: no other run holds this file
  ::close(lock_fd_);
  lock_fd_ = -1;
}

OutputSet::~OutputSet() {
  if (!staging_.empty()) {
    std::error_code ec;
    if (committed_) {
      remove_windplan_files(staging_, &previous_);  // the previous set's verified files only
    } else {
      fs::remove_all(staging_, ec);  // the unfinished new set, in the folder this run made
    }
    remove_handlers();
  }
  release_lock();
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

  // The folder again, as it is now (a user may have put a file in it during the run): only the
  // files verified here are removed with the previous set.
  struct stat st {};
  const bool exists = ::lstat(dir_.c_str(), &st) == 0;
  if (exists && !S_ISDIR(st.st_mode)) {
    throw IoError(dir_.string() + ": is no longer a folder; the new set is not moved in");
  }
  previous_ = exists ? verify_output_folder(dir_) : std::vector<std::string>{};

  // The swap: after it, staging_ names the previous set (or nothing).
  const fs::path parent = dir_.parent_path();
  if (exists) {
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
  // The previous set: exactly the verified files. Anything that arrived since stays, in the
  // staging folder's name, which the next run leaves alone but for windplan's own files.
  remove_windplan_files(staging_, &previous_);
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
