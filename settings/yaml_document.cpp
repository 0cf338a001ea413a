#include "settings/yaml_document.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <vector>

#include "core/error.hpp"
#include "core/text_file.hpp"

namespace thetad {

namespace {

[[noreturn]] void fail(const std::string& source, const YAML::Mark& mark, const std::string& reason) {
  std::ostringstream message;
  message << source << ":" << mark.line + 1 << ":" << mark.column + 1 << ": " << reason;
  throw Error(message.str());
}

// The position of byte `offset` of `text`.
YAML::Mark mark_of(const std::string& text, std::size_t offset) {
  YAML::Mark mark;
  mark.pos = static_cast<int>(offset);
  mark.line = static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
  const std::size_t line_start = text.rfind('\n', offset == 0 ? 0 : offset - 1);
  mark.column = static_cast<int>(line_start == std::string::npos || offset == 0 ? offset : offset - line_start - 1);
  return mark;
}

// A key as written, for comparing keys: scalars by their text, other keys by their dump.
std::string key_text(const YAML::Node& key) { return key.IsScalar() ? key.Scalar() : YAML::Dump(key); }

class DocumentCheck {
 public:
  explicit DocumentCheck(const std::string& source) : source_(source) {}

  void visit(const YAML::Node& node) {
    if (++nodes_ > kMaxYamlNodes)
      fail(source_, node.Mark(),
           "the document expands (through aliases) to more than " + std::to_string(kMaxYamlNodes) + " nodes");
    if (node.IsSequence()) {
      for (const auto& item : node) visit(item);
    } else if (node.IsMap()) {
      std::vector<std::pair<std::string, YAML::Mark>> keys;
      for (const auto& item : node) {
        const std::string key = key_text(item.first);
        const auto same = [&](const auto& seen) { return seen.first == key; };
        if (const auto first = std::find_if(keys.begin(), keys.end(), same); first != keys.end())
          fail(source_, item.first.Mark(),
               "key '" + key + "' given twice in one map (first at line " + std::to_string(first->second.line + 1) +
                   "); a duplicate would silently be ignored");
        keys.emplace_back(key, item.first.Mark());
        visit(item.first);
        visit(item.second);
      }
    }
  }

 private:
  const std::string& source_;
  long nodes_ = 0;
};

}  // namespace

YAML::Node parse_yaml(const std::string& text, const std::string& source) {
  if (const std::size_t bad = invalid_utf8(text); bad != std::string::npos)
    fail(source, mark_of(text, bad), "not valid UTF-8 (byte " + std::to_string(bad) + ")");
  // YAML's printable set: no C0 control but tab, line feed and carriage return, no DEL. A NUL
  // would also make yaml-cpp read the text as UTF-16 or UTF-32.
  const auto control = std::find_if(text.begin(), text.end(), [](char c) {
    const auto byte = static_cast<unsigned char>(c);
    return (byte < 0x20 && byte != '\t' && byte != '\n' && byte != '\r') || byte == 0x7F;
  });
  if (control != text.end()) {
    const auto at = static_cast<std::size_t>(control - text.begin());
    char code[8];
    std::snprintf(code, sizeof code, "0x%02X", static_cast<unsigned char>(*control));
    fail(source, mark_of(text, at), std::string("control character ") + code + " (byte " + std::to_string(at) +
                                        "): not allowed in YAML");
  }
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& error) {
    // yaml-cpp's what() carries 0-based positions; print ours, 1-based.
    fail(source, error.mark, "invalid YAML: " + escaped_utf8(error.msg));
  }
  DocumentCheck(source).visit(root);
  return root;
}

YAML::Node load_yaml_file(const std::filesystem::path& file) { return parse_yaml(read_text_file(file), file.string()); }

}  // namespace thetad
