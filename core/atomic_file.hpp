#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

namespace thetad {

// A file being written under a temporary name unique to this process and this write
// (".NAME.<pid>.<n>.partial" beside the final name), so that two thetad processes writing into one
// folder never share one. Durable: the content reaches the disk (fsync) before the rename, and the
// rename before commit() returns, so after a power loss the final name holds the old file or the
// new one, never a torn one (docs/reliability.md). It is removed when the object dies without
// commit(), and on SIGINT, SIGTERM or SIGHUP: the handler removes every open partial file, then
// passes the signal on to what handled it before (the default action ends the process as the
// signal would have).
class PartialFile {
 public:
  explicit PartialFile(const std::filesystem::path& final_path);
  ~PartialFile();
  PartialFile(const PartialFile&) = delete;
  PartialFile& operator=(const PartialFile&) = delete;

  const std::filesystem::path& path() const { return partial_; }
  const std::filesystem::path& final_path() const { return final_; }
  // Writes the partial file's content (`write` fills the stream) and flushes it to disk. Throws
  // thetad::Error naming the final file when it cannot be opened or the writing or flushing fails
  // (a full disk, a file size limit, an I/O error).
  void write(const std::function<void(std::ostream&)>& write);

  // Renames the partial file onto the final name (atomic on one file system) and flushes the new
  // entry to disk (sync_entry). Throws thetad::Error naming both when the rename fails (the partial
  // file is then removed), or naming the folder when its flush fails (the file then stands under
  // its final name, but may not survive a power loss).
  void commit();

 private:
  std::filesystem::path final_;
  std::filesystem::path partial_;
  int slot_ = -1;  // in the signal handler's table
  bool committed_ = false;
};

// Flushes the entry of `file` in its folder (made, renamed or removed) to disk, and the folder's
// own entry in its parent (the folder may be new, e.g. a run's --out made just before): fsync on
// the two directories. Throws thetad::Error naming the folder and the reason.
void sync_entry(const std::filesystem::path& file);

// Writes `content` to `path` through a PartialFile, so a reader never sees half a file. Creates the
// directory if needed. Throws thetad::Error naming the path and the reason; nothing is left behind.
void write_file_atomically(const std::filesystem::path& path, const std::string& content);

}  // namespace thetad
