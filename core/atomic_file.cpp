#include "core/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <iterator>
#include <mutex>

#include "core/error.hpp"

namespace thetad {

namespace {

// The signal handler may only read memory and call async-signal-safe functions (unlink,
// sigaction, raise), so the open partial files are kept in a fixed table of C strings, each slot
// free, being claimed (its name being written) or ready (the handler may unlink its name).
constexpr int kSlots = 256;
constexpr std::size_t kPathBytes = 4096;
enum SlotState : int { kFree, kClaiming, kReady };
struct Slot {
  std::atomic<int> state{kFree};
  char path[kPathBytes];
};
std::array<Slot, kSlots> slots;
std::atomic<unsigned long> next_number{0};

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction previous_actions[std::size(kSignals)];

extern "C" void remove_partial_files(int signal_number) {
  for (Slot& slot : slots) {
    if (slot.state.load() == kReady) unlink(slot.path);
  }
  // Then whatever handled the signal before (a host program's, e.g. Python's KeyboardInterrupt),
  // or the default action, which ends the process as the signal would have.
  for (std::size_t i = 0; i < std::size(kSignals); ++i) {
    if (kSignals[i] != signal_number) continue;
    const struct sigaction& previous = previous_actions[i];
    if (previous.sa_handler == SIG_DFL) {
      sigaction(signal_number, &previous, nullptr);
      raise(signal_number);
    } else if ((previous.sa_flags & SA_SIGINFO) == 0 && previous.sa_handler != SIG_IGN) {
      previous.sa_handler(signal_number);
    }
  }
}

void install_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (std::size_t i = 0; i < std::size(kSignals); ++i) {
      sigaction(kSignals[i], nullptr, &previous_actions[i]);
      // A signal someone chose to ignore stays ignored (nohup); one handled with siginfo is left to
      // its handler, which this one could not call correctly.
      if (previous_actions[i].sa_handler == SIG_IGN || (previous_actions[i].sa_flags & SA_SIGINFO) != 0) continue;
      struct sigaction action {};
      action.sa_handler = remove_partial_files;
      sigemptyset(&action.sa_mask);
      sigaction(kSignals[i], &action, nullptr);
    }
  });
}

// A slot holding `path` for the signal handler, or -1 when none is free (or the path is too long):
// then the file is still removed by its PartialFile, only not on a signal.
int claim_slot(const std::filesystem::path& path) {
  const std::string text = path.string();
  if (text.size() >= kPathBytes) return -1;
  for (int i = 0; i < kSlots; ++i) {
    Slot& slot = slots[static_cast<std::size_t>(i)];
    int expected = kFree;
    if (!slot.state.compare_exchange_strong(expected, kClaiming)) continue;
    std::memcpy(slot.path, text.c_str(), text.size() + 1);
    slot.state.store(kReady);  // published only once the name is whole
    return i;
  }
  return -1;
}

// fsync(2) on `path` opened read-only (Linux flushes a file whatever the mode of the descriptor):
// 0, or the errno of the open or the fsync.
int sync_path(const std::filesystem::path& path, int flags) {
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC | flags);
  if (fd < 0) return errno;
  const int reason = fsync(fd) == 0 ? 0 : errno;
  close(fd);
  return reason;
}

void sync_directory(const std::filesystem::path& folder) {
  if (const int reason = sync_path(folder, O_DIRECTORY); reason != 0)
    throw Error("cannot flush the folder " + folder.string() + " to disk: " + std::strerror(reason));
}

}  // namespace

void sync_entry(const std::filesystem::path& file) {
  const std::filesystem::path folder = std::filesystem::absolute(file).parent_path();
  sync_directory(folder);
  sync_directory(folder.parent_path());
}

PartialFile::PartialFile(const std::filesystem::path& final_path) : final_(final_path) {
  install_handlers();
  std::string name = ".";
  name += final_.filename().string();
  name += '.';
  name += std::to_string(getpid());
  name += '.';
  name += std::to_string(next_number++);
  name += ".partial";
  partial_ = final_.parent_path() / name;
  slot_ = claim_slot(partial_);
}

PartialFile::~PartialFile() {
  if (!committed_) {
    std::error_code ignored;
    std::filesystem::remove(partial_, ignored);
  }
  if (slot_ >= 0) slots[static_cast<std::size_t>(slot_)].state.store(kFree);
}

void PartialFile::write(const std::function<void(std::ostream&)>& write) {
  std::ofstream out(partial_, std::ios::binary | std::ios::trunc);
  if (!out) throw Error("cannot write " + final_.string() + ": " + std::strerror(errno));
  errno = 0;
  write(out);
  out.flush();
  // The reason of the write(2) that failed (ENOSPC, EFBIG under a file size limit, EIO), taken
  // before close() can overwrite it.
  const int reason = out ? 0 : errno;
  out.close();
  if (!out)
    throw Error("cannot write " + final_.string() + ": " + (reason != 0 ? std::strerror(reason) : "write error") +
                " (nothing was written under that name)");
  // Before the rename: else a power loss may leave the final name on an empty or torn file.
  if (const int flush = sync_path(partial_, 0); flush != 0)
    throw Error("cannot write " + final_.string() + ": " + std::strerror(flush) + " (nothing was written under that name)");
}

void PartialFile::commit() {
  std::error_code error;
  std::filesystem::rename(partial_, final_, error);
  if (error) throw Error("cannot rename " + partial_.string() + " to " + final_.string() + ": " + error.message());
  committed_ = true;
  sync_entry(final_);
}

void write_file_atomically(const std::filesystem::path& path, const std::string& content) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.has_parent_path()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw Error("cannot create directory " + path.parent_path().string() + ": " + ec.message());
  }
  PartialFile file(path);
  file.write([&](std::ostream& out) { out.write(content.data(), static_cast<std::streamsize>(content.size())); });
  file.commit();
}

}  // namespace thetad
