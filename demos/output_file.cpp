#include "output_file.h"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/file.h>
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
  // Lock before truncating, so that a refused second writer leaves the file alone.
  lock_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0666);
  if (lock_ < 0) refuse(std::strerror(errno));
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
