#pragma once
// Files the tools write (the runner's --csv and --trajectory, export -o): every
// write is checked, and a file is written by one process at a time.
//
// Two runs given the same output path would interleave their rows; instead,
// each output file is locked (flock, exclusive) while it is written, and a
// second writer is refused at once. Readers are not locked out.
#include <fstream>
#include <stdexcept>
#include <string>

namespace scenes {

// A write or close of an output file failed (a full disk, a device such as
// /dev/full, an I/O error): what() is one line naming the file and the cause.
// The tools end with exit code 4.
class WriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws WriteError "cannot write <what> file '<path>': <reason of errno>".
[[noreturn]] void throwWriteError(const std::string& what, const std::string& path);

class OutputFile {
 public:
  // Creates or empties the file at path. what names it in errors ("--csv").
  // Throws std::invalid_argument when it cannot be opened or another process
  // is writing it.
  OutputFile(std::string path, std::string what);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::ostream& stream() { return out_; }
  // Throws WriteError when any write so far failed.
  void check();
  // Flushes and closes the file (and releases the lock); throws WriteError
  // when that or any earlier write failed.
  void close();

 private:
  std::string path_, what_;
  int lock_ = -1;  // descriptor holding the flock
  std::ofstream out_;
};

}  // namespace scenes
