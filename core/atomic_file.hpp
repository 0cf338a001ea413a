#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

namespace thetad {

// A file being written under a temporary name unique to this process and this write
// (".NAME.<pid>.<n>.partial" beside the final name), so that two thetad processes writing into one
// folder never share one. It is removed when the object dies without commit(), and on SIGINT,
// SIGTERM or SIGHUP: the handler removes every open partial file, then passes the signal on to
// what handled it before (the default action ends the process as the signal would have).
class PartialFile {
 public:
  explicit PartialFile(const std::filesystem::path& final_path);
  ~PartialFile();
  PartialFile(const PartialFile&) = delete;
  PartialFile& operator=(const PartialFile&) = delete;

  const std::filesystem::path& path() const { return partial_; }
  const std::filesystem::path& final_path() const { return final_; }
  // Writes the partial file's content: `write` fills the stream. Throws thetad::Error naming the
  // final file when it cannot be opened or the writing fails (a full disk, a file size limit).
  void write(const std::function<void(std::ostream&)>& write);

  // Renames the partial file onto the final name (atomic on one file system). Throws thetad::Error
  // naming both on failure (the partial file is then removed).
  void commit();

 private:
  std::filesystem::path final_;
  std::filesystem::path partial_;
  int slot_ = -1;  // in the signal handler's table
  bool committed_ = false;
};

// Writes `content` to `path` through a PartialFile, so a reader never sees half a file. Creates the
// directory if needed. Throws thetad::Error naming the path and the reason; nothing is left behind.
void write_file_atomically(const std::filesystem::path& path, const std::string& content);

}  // namespace thetad
