#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace thetad {

// Input files (scenarios, settings, tables, results) are read whole, so a path that is not a
// regular file (a directory, a device such as /dev/zero, a FIFO) or that is larger than this is
// refused before anything is read: the largest file thetad writes for itself to read back (an
// lqr-scheduled table of a fine grid) is a few MiB.
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{64} << 20;

// The bytes of `file`. Throws thetad::Error naming the file and the reason (missing, not a regular
// file, over kMaxInputFileBytes, unreadable).
std::string read_text_file(const std::filesystem::path& file);

// The byte offset of the first sequence of `text` that is not valid UTF-8 (RFC 3629: overlong
// forms, surrogates and code points above U+10FFFF are invalid), or npos when it is all valid.
// Names and labels end up in JSON results and file names, which accept nothing else.
std::size_t invalid_utf8(const std::string& text);

// `text` with every byte that is not part of valid UTF-8 written as \xHH: for quoting what a
// library says about bad input (its messages may carry the raw bytes) in a message of ours.
std::string escaped_utf8(const std::string& text);

}  // namespace thetad
