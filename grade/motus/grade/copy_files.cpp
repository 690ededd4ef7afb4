#include "motus/grade/copy_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace fs = std::filesystem;

namespace motus::grade {

namespace {

// A descriptor closed however the copy is left.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

[[noreturn]] void cannot_write(const std::string& to, int error) {
  throw std::runtime_error(to + ": could not be written (" + std::strerror(error) + ")");
}

}  // namespace

void copy_file_told(const std::string& from, const std::string& to) {
  Descriptor in{::open(from.c_str(), O_RDONLY | O_CLOEXEC)};
  if (in.fd < 0) throw std::runtime_error(from + ": could not be read (" + std::strerror(errno) + ")");
  struct stat source {};
  if (::fstat(in.fd, &source) != 0) throw std::runtime_error(from + ": could not be read (" + std::strerror(errno) + ")");
  Descriptor out{::open(to.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644)};
  if (out.fd < 0) cannot_write(to, errno);
  ::fchmod(out.fd, source.st_mode & 0777);  // (as copy_file: a script stays one)
  char buffer[1 << 16];
  for (;;) {
    const ssize_t got = ::read(in.fd, buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw std::runtime_error(from + ": could not be read (" + std::strerror(errno) + ")");
    if (got == 0) break;
    for (ssize_t done = 0; done < got;) {
      const ssize_t put = ::write(out.fd, buffer + done, static_cast<size_t>(got - done));
      if (put < 0 && errno == EINTR) continue;
      if (put < 0) cannot_write(to, errno);
      done += put;
    }
  }
  // (A delayed write's failure, on a file system that reports it only then, is a failure too.)
  const int fd = out.fd;
  out.fd = -1;
  if (::close(fd) != 0) cannot_write(to, errno);
}

void copy_tree_told(const std::string& from, const std::string& to) {
  if (!fs::is_directory(from)) return copy_file_told(from, to);
  std::error_code error;
  fs::create_directories(to, error);
  if (error) cannot_write(to, error.value());
  for (fs::recursive_directory_iterator e(from, fs::directory_options::follow_directory_symlink), end; e != end; ++e) {
    const fs::path target = fs::path(to) / e->path().lexically_relative(from);  // (not fs::relative: it resolves links)
    if (e->is_directory()) {
      fs::create_directories(target, error);
      if (error) cannot_write(target.string(), error.value());
    } else if (e->is_regular_file()) {
      copy_file_told(e->path().string(), target.string());
    }
  }
}

}  // namespace motus::grade
