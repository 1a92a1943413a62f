#pragma once
// Files the tools write (the runner's --csv and --trajectory, export -o, the
// laboratory's CSVs, tables, values and shards): every write is checked, a
// file is written by one process at a time, and a file of the asked name is
// only ever complete.
//
// A regular file is written under a temporary name beside it, PATH.partial,
// and renamed to PATH when it is closed: a run killed or cut off mid-write
// leaves PATH as it was (absent, or the previous complete file) and at most a
// PATH.partial. A device (/dev/null, /dev/full, a terminal, /dev/stdout on a
// terminal) is written directly. Two runs given the same output path would
// interleave their rows; instead, the file being written (PATH.partial, or the
// device) is locked (flock, exclusive) and a second writer is refused at once.
// Readers are not locked out.
#include <fstream>
#include <stdexcept>
#include <string>

namespace output {

// A write or close of an output file failed (a full disk, a device such as
// /dev/full, an I/O error): what() is one line naming the file and the cause.
// The tools end with exit code 4.
class WriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws WriteError "cannot write <what> file '<path>': <reason of errno>".
[[noreturn]] void throwWriteError(const std::string& what, const std::string& path);

// The temporary name a regular output file is written under until closed.
std::string partialPath(const std::string& path);

class OutputFile {
 public:
  // Starts the file at path (PATH.partial for a regular file). what names it
  // in errors ("--csv"). Throws std::invalid_argument when it cannot be
  // opened or another process is writing it.
  OutputFile(std::string path, std::string what);
  // Not closed: at the end of a scope the file is closed and renamed as by
  // close() (errors cannot be reported here); while an exception unwinds, the
  // partial file is removed and PATH left as it was.
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::ostream& stream() { return out_; }
  // Throws WriteError when any write so far failed.
  void check();
  // Flushes and closes the file, renames PATH.partial to PATH, and releases
  // the lock; throws WriteError when that or any earlier write failed.
  void close();

 private:
  void finish();   // flush, close, rename; throws WriteError
  void abandon();  // close and remove the partial file; never throws

  std::string path_, what_;
  std::string writtenPath_;  // PATH.partial, or PATH for a device
  std::string finalPath_;    // where the partial file is renamed (a symlink's target); empty for a device
  int lock_ = -1;            // descriptor holding the flock
  int unwinding_ = 0;        // std::uncaught_exceptions() when opened
  std::ofstream out_;
};

}  // namespace output
