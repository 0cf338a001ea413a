#include "core/atomic_file.hpp"

#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <mutex>

#include "core/error.hpp"

namespace thetad {

namespace {

// The signal handler may only read memory and call async-signal-safe functions (unlink, signal,
// raise), so the open partial files are kept in a fixed table of C strings with atomic flags.
constexpr int kSlots = 256;
constexpr std::size_t kPathBytes = 4096;
struct Slot {
  std::atomic<bool> used{false};
  char path[kPathBytes];
};
std::array<Slot, kSlots> slots;
std::atomic<unsigned long> next_number{0};

extern "C" void remove_partial_files(int signal_number) {
  for (Slot& slot : slots) {
    if (slot.used.load()) unlink(slot.path);
  }
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

void install_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction action {};
      action.sa_handler = remove_partial_files;
      sigemptyset(&action.sa_mask);
      struct sigaction previous {};
      sigaction(signal_number, nullptr, &previous);
      // A signal someone chose to ignore stays ignored (nohup).
      if (previous.sa_handler != SIG_IGN) sigaction(signal_number, &action, nullptr);
    }
  });
}

int claim_slot(const std::filesystem::path& path) {
  const std::string text = path.string();
  if (text.size() >= kPathBytes) return -1;
  for (int i = 0; i < kSlots; ++i) {
    Slot& slot = slots[static_cast<std::size_t>(i)];
    bool expected = false;
    if (slot.used.load() || !slot.used.compare_exchange_strong(expected, true)) continue;
    // Marked used before its path is complete: the handler would unlink a prefix at worst, and
    // the name is written before any file exists under it.
    std::memcpy(slot.path, text.c_str(), text.size() + 1);
    return i;
  }
  return -1;
}

}  // namespace

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
  if (slot_ >= 0) slots[static_cast<std::size_t>(slot_)].used.store(false);
}

void PartialFile::commit() {
  std::error_code error;
  std::filesystem::rename(partial_, final_, error);
  if (error) throw Error("cannot rename " + partial_.string() + " to " + final_.string() + ": " + error.message());
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& path, const std::string& content) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.has_parent_path()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw Error("cannot create directory " + path.parent_path().string() + ": " + ec.message());
  }
  PartialFile file(path);
  {
    std::ofstream out(file.path(), std::ios::binary | std::ios::trunc);
    if (!out) throw Error("cannot write " + path.string() + ": " + std::strerror(errno));
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.close();
    if (!out) throw Error("writing " + path.string() + " failed (disk full or file too large?)");
  }
  file.commit();
}

}  // namespace thetad
