#include "core/text_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>

#include "core/error.hpp"

namespace thetad {

namespace fs = std::filesystem;

namespace {

const char* kind_of(fs::file_type type) {
  switch (type) {
    case fs::file_type::directory: return "a directory";
    case fs::file_type::block: return "a block device";
    case fs::file_type::character: return "a character device";
    case fs::file_type::fifo: return "a FIFO (named pipe)";
    case fs::file_type::socket: return "a socket";
    default: return "not a regular file";
  }
}

// The length of the UTF-8 sequence starting at text[i], or 0 when it is invalid.
std::size_t utf8_sequence(const std::string& text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  if (lead < 0x80) return 1;
  std::size_t length = 0;
  unsigned char low = 0x80, high = 0xBF;  // the range of the second byte
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    if (lead == 0xE0) low = 0xA0;
    if (lead == 0xED) high = 0x9F;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    if (lead == 0xF0) low = 0x90;
    if (lead == 0xF4) high = 0x8F;
  } else {
    return 0;
  }
  if (i + length > text.size()) return 0;
  if (byte(i + 1) < low || byte(i + 1) > high) return 0;
  for (std::size_t k = 2; k < length; ++k) {
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  }
  return length;
}

}  // namespace

std::string read_text_file(const fs::path& file) {
  // A path from the command line may hold any bytes; the message must still be UTF-8.
  const std::string cannot_read = "cannot read " + escaped_utf8(file.string()) + ": ";
  std::error_code error;
  const fs::file_status status = fs::status(file, error);
  if (error) throw Error(cannot_read + error.message());
  if (status.type() != fs::file_type::regular)
    throw Error(cannot_read + kind_of(status.type()) + ", not a regular file");
  const std::uintmax_t size = fs::file_size(file, error);
  if (error) throw Error(cannot_read + error.message());
  if (size > kMaxInputFileBytes)
    throw Error(cannot_read + std::to_string(size) + " bytes, more than the " +
                std::to_string(kMaxInputFileBytes >> 20) + " MiB an input file may have");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(cannot_read + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error(cannot_read + "read error");
  return text.str();
}

std::string escaped_utf8(const std::string& text) {
  std::string escaped;
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t length = utf8_sequence(text, i);
    if (length > 0) {
      escaped.append(text, i, length);
      i += length;
      continue;
    }
    char hex[8];
    std::snprintf(hex, sizeof hex, "\\x%02X", static_cast<unsigned char>(text[i]));
    escaped.append(hex);
    ++i;
  }
  return escaped;
}

std::size_t invalid_utf8(const std::string& text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t length = utf8_sequence(text, i);
    if (length == 0) return i;
    i += length;
  }
  return std::string::npos;
}

}  // namespace thetad
