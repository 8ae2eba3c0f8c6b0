#include "geometry/base/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "geometry/base/errors.h"

namespace windplan {

namespace {

// Opens without blocking and checks the kind and size; returns the descriptor (caller closes).
int open_checked(const std::filesystem::path& path, std::uintmax_t cap, const std::string& what,
                 std::uintmax_t* size) {
  const std::string p = path.empty() ? std::string("(empty path)") : path.string();
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    const int err = errno;
    if (err == ENOENT) throw IoError(p + ": no such file");
    throw IoError(p + ": cannot open: " + std::strerror(err));
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    throw IoError(p + ": cannot read its status: " + std::strerror(err));
  }
  const char* kind = nullptr;
  if (S_ISDIR(st.st_mode)) {
    kind = "is a directory";
  } else if (S_ISFIFO(st.st_mode)) {
    kind = "is a FIFO (named pipe)";
  } else if (S_ISCHR(st.st_mode)) {
    kind = "is a character device (like /dev/zero or a terminal)";
  } else if (S_ISBLK(st.st_mode)) {
    kind = "is a block device";
  } else if (S_ISSOCK(st.st_mode)) {
    kind = "is a socket";
  } else if (!S_ISREG(st.st_mode)) {
    kind = "is not a regular file";
  }
  if (kind) {
    ::close(fd);
    throw IoError(p + ": " + kind + ", not a file; give " + what);
  }
  *size = static_cast<std::uintmax_t>(st.st_size);
  if (*size > cap) {
    ::close(fd);
    throw IoError(p + ": is " + byte_size_text(*size) + ", above the bound of " +
                  byte_size_text(cap) + " for " + what);
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  return fd;
}

}  // namespace

std::string byte_size_text(std::uintmax_t bytes) {
  char buf[64];
  if (bytes < 10000000) {
    std::snprintf(buf, sizeof buf, "%ju bytes", bytes);
  } else if (bytes < 1000000000ull) {
    std::snprintf(buf, sizeof buf, "%.4g MB", static_cast<double>(bytes) / 1e6);
  } else {
    std::snprintf(buf, sizeof buf, "%.4g GB", static_cast<double>(bytes) / 1e9);
  }
  return buf;
}

std::uintmax_t check_input_file(const std::filesystem::path& path, std::uintmax_t cap,
                                const std::string& what) {
  std::uintmax_t size = 0;
  ::close(open_checked(path, cap, what, &size));
  return size;
}

std::string read_input_file(const std::filesystem::path& path, std::uintmax_t cap,
                            const std::string& what) {
  std::uintmax_t size = 0;
  const int fd = open_checked(path, cap, what, &size);
  std::string data;
  data.resize(static_cast<std::size_t>(size) + 1);
  std::size_t got = 0;
  for (;;) {
    if (got == data.size()) {
      if (data.size() > cap) break;
      data.resize(std::min<std::uintmax_t>(cap + 1, data.size() * 2 + 4096));
    }
    const ssize_t n = ::read(fd, data.data() + got, data.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      throw IoError(path.string() + ": read error: " + std::strerror(err));
    }
    if (n == 0) break;
    got += static_cast<std::size_t>(n);
  }
  ::close(fd);
  if (got > cap) {
    throw IoError(path.string() + ": grew above the bound of " + byte_size_text(cap) + " for " +
                  what + " while read");
  }
  data.resize(got);
  return data;
}

}  // namespace windplan
