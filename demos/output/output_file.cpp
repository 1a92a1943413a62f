#include "output/output_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace output {

void throwWriteError(const std::string& what, const std::string& path) {
  const int error = errno;
  throw WriteError("cannot write " + what + " file '" + path + "': " +
                   (error ? std::strerror(error) : "the write failed"));
}

std::string partialPath(const std::string& path) { return path + ".partial"; }

OutputFile::OutputFile(std::string path, std::string what)
    : path_(std::move(path)), what_(std::move(what)), unwinding_(std::uncaught_exceptions()) {
  const auto refuse = [&](const std::string& why) {
    if (lock_ >= 0) ::close(lock_);
    lock_ = -1;
    throw std::invalid_argument("cannot write " + what_ + " file '" + path_ + "': " + why);
  };
  if (path_.empty()) refuse("expected a file name, got an empty one");
  // Only a regular file or a device (/dev/null, /dev/full, a terminal): a FIFO
  // or socket would block or interleave. A regular file that is also the tool's
  // stdout or stderr (--csv /dev/stdout redirected to a file) is refused: its
  // header would be overwritten by the summary or the error line, which write
  // at their own offset.
  struct stat existing {};
  const bool exists = ::stat(path_.c_str(), &existing) == 0;
  const auto same = [&](int fd) {
    struct stat other {};
    return ::fstat(fd, &other) == 0 && other.st_dev == existing.st_dev && other.st_ino == existing.st_ino;
  };
  if (exists && S_ISDIR(existing.st_mode)) refuse(std::strerror(EISDIR));
  if (exists && !S_ISREG(existing.st_mode) && !S_ISCHR(existing.st_mode))
    refuse("not a regular file or device (a FIFO or socket)");
  if (exists && S_ISREG(existing.st_mode) && (same(STDOUT_FILENO) || same(STDERR_FILENO)))
    refuse("it is also the standard output or error, where the summary and messages go");
  const bool device = exists && S_ISCHR(existing.st_mode);
  if (device) {
    writtenPath_ = path_;
  } else {
    // A symlink to a file: the file it names is replaced, the link kept.
    std::error_code error;
    finalPath_ = path_;
    if (std::filesystem::is_symlink(std::filesystem::symlink_status(path_, error))) {
      finalPath_ = std::filesystem::weakly_canonical(path_, error).string();
      if (error) refuse(error.message());
    }
    // An existing file that this user may not write stays refused, although
    // its directory would allow replacing it.
    if (exists && ::access(path_.c_str(), W_OK) != 0) refuse(std::strerror(errno));
    writtenPath_ = partialPath(finalPath_);
  }
  // Lock before truncating, so that a refused second writer leaves the file alone.
  // O_NONBLOCK: a FIFO with no reader fails at once (ENXIO) instead of waiting.
  lock_ = ::open(writtenPath_.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | O_NONBLOCK | (device ? 0 : O_NOFOLLOW), 0666);
  if (lock_ < 0) refuse(errno == ENXIO ? "not a regular file or device (a FIFO or socket)" : std::strerror(errno));
  struct stat opened {};
  if (::fstat(lock_, &opened) != 0) refuse(std::strerror(errno));
  if (device ? !S_ISCHR(opened.st_mode) : !S_ISREG(opened.st_mode))
    refuse("'" + writtenPath_ + "' is not a regular file or device");
  if (::flock(lock_, LOCK_EX | LOCK_NB) != 0)
    refuse(errno == EWOULDBLOCK ? "another process is writing it" : std::strerror(errno));
  if (!device) {
    if (::ftruncate(lock_, 0) != 0) refuse(std::strerror(errno));
    if (exists) ::fchmod(lock_, existing.st_mode & 07777);  // the replaced file's permissions
  }
  out_.open(writtenPath_, std::ios::out | std::ios::trunc | std::ios::binary);
  if (!out_) refuse(std::strerror(errno));
}

OutputFile::~OutputFile() {
  if (!out_.is_open()) return;
  if (std::uncaught_exceptions() > unwinding_) {
    abandon();
    return;
  }
  try {
    finish();
  } catch (const WriteError&) {
    abandon();
  }
}

void OutputFile::check() {
  if (!out_) throwWriteError(what_, path_);
}

void OutputFile::finish() {
  check();
  errno = 0;
  out_.close();  // flushes: a full disk may show only here
  if (!out_) throwWriteError(what_, path_);
  if (!finalPath_.empty() && std::rename(writtenPath_.c_str(), finalPath_.c_str()) != 0)
    throwWriteError(what_, path_);
  if (lock_ >= 0) ::close(lock_);
  lock_ = -1;
}

void OutputFile::abandon() {
  if (out_.is_open()) out_.close();
  if (!finalPath_.empty() && lock_ >= 0) ::unlink(writtenPath_.c_str());
  if (lock_ >= 0) ::close(lock_);
  lock_ = -1;
}

void OutputFile::close() {
  try {
    finish();
  } catch (const WriteError&) {
    abandon();
    throw;
  }
}

}  // namespace output
