#include "output_file.h"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace scenes {

void throwWriteError(const std::string& what, const std::string& path) {
  const int error = errno;
  throw WriteError("cannot write " + what + " file '" + path + "': " +
                   (error ? std::strerror(error) : "the write failed"));
}

OutputFile::OutputFile(std::string path, std::string what) : path_(std::move(path)), what_(std::move(what)) {
  const auto refuse = [&](const std::string& why) {
    throw std::invalid_argument("cannot write " + what_ + " file '" + path_ + "': " + why);
  };
  if (path_.empty()) refuse("expected a file name, got an empty one");
  // Lock before truncating, so that a refused second writer leaves the file alone.
  // O_NONBLOCK: a FIFO with no reader fails at once (ENXIO) instead of waiting.
  lock_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | O_NONBLOCK, 0666);
  if (lock_ < 0) refuse(errno == ENXIO ? "not a regular file or device (a FIFO or socket)" : std::strerror(errno));
  // Only a regular file or a device (/dev/null, /dev/full, a terminal): a FIFO
  // or socket would block or interleave. A regular file that is also the tool's
  // stdout or stderr (--csv /dev/stdout redirected to a file) is refused: its
  // header would be overwritten by the summary or the error line, which write
  // at their own offset.
  struct stat info {};
  const auto same = [&](int fd) {
    struct stat other {};
    return ::fstat(fd, &other) == 0 && other.st_dev == info.st_dev && other.st_ino == info.st_ino;
  };
  const char* why = nullptr;
  if (::fstat(lock_, &info) != 0)
    why = std::strerror(errno);
  else if (!S_ISREG(info.st_mode) && !S_ISCHR(info.st_mode))
    why = "not a regular file or device (a FIFO or socket)";
  else if (S_ISREG(info.st_mode) && (same(STDOUT_FILENO) || same(STDERR_FILENO)))
    why = "it is also the standard output or error, where the summary and messages go";
  if (why) {
    const std::string reason = why;
    ::close(lock_);
    lock_ = -1;
    refuse(reason);
  }
  if (::flock(lock_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(lock_);
    lock_ = -1;
    refuse(error == EWOULDBLOCK ? "another process is writing it" : std::strerror(error));
  }
  out_.open(path_, std::ios::out | std::ios::trunc | std::ios::binary);
  if (!out_) refuse(std::strerror(errno));
}

OutputFile::~OutputFile() {
  if (out_.is_open()) out_.close();
  if (lock_ >= 0) ::close(lock_);
}

void OutputFile::check() {
  if (!out_) throwWriteError(what_, path_);
}

void OutputFile::close() {
  check();
  errno = 0;
  out_.close();  // flushes: a full disk may show only here
  if (!out_) throwWriteError(what_, path_);
  if (lock_ >= 0) ::close(lock_);
  lock_ = -1;
}

}  // namespace scenes
