// The rules every YAML file of thetad is parsed with (settings/yaml_document.hpp).
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/text_file.hpp"
#include "settings/yaml_document.hpp"
#include "tests/error_message.hpp"

namespace thetad {
namespace {

using ::testing::HasSubstr;

std::string error_of(const std::string& text) {
  return testing::error_message([&] { parse_yaml(text, "f.yaml"); });
}

TEST(YamlDocument, ADuplicateKeyNamesBothLinesAtAnyDepth) {
  EXPECT_THAT(error_of("a: 1\nb:\n  c: 2\n  c: 3\n"), HasSubstr("f.yaml:4:3: key 'c' given twice in one map (first at line 3)"));
  EXPECT_THAT(error_of("- {x: 1, x: 2}\n"), HasSubstr("f.yaml:1:10: key 'x' given twice"));
  EXPECT_NO_THROW(parse_yaml("a: {c: 1}\nb: {c: 1}\n", "f.yaml"));  // the same key in two maps is fine
}

TEST(YamlDocument, TextMustBeUtf8WithoutControlCharacters) {
  EXPECT_THAT(error_of("name: ok\nother: \"b\xc3\"\n"), HasSubstr("f.yaml:2:10: not valid UTF-8 (byte 18)"));
  EXPECT_THAT(error_of("name: \xed\xa0\x80\n"), HasSubstr("not valid UTF-8"));  // a surrogate
  EXPECT_THAT(error_of("name: \xc0\xaf\n"), HasSubstr("not valid UTF-8"));      // an overlong '/'
  EXPECT_THAT(error_of(std::string("a: 1\nb: x\0y\n", 12)), HasSubstr("f.yaml:2:5: control character 0x00 (byte 9)"));
  EXPECT_NO_THROW(parse_yaml("name: \"caf\xc3\xa9 \xf0\x9f\x9a\x81\"\r\nnote: \"a\tb\"\n", "f.yaml"));  // tab, CR: allowed
}

TEST(YamlDocument, WhatYamlCppSaysIsQuotedAsUtf8) {
  // An escape yaml-cpp does not know, with a byte that is not UTF-8 on its own in its message.
  const std::string message = error_of("a: \"\\\xc3\xa9\"\n");
  EXPECT_THAT(message, HasSubstr("f.yaml:1:"));
  EXPECT_THAT(message, HasSubstr("invalid YAML"));
  EXPECT_EQ(invalid_utf8(message), std::string::npos) << message;
  EXPECT_EQ(escaped_utf8("a\xf2z\xc3\xa9"), "a\\xF2z\xc3\xa9");
}

TEST(YamlDocument, AliasesMayNotExpandWithoutBound) {
  // Level i is a list of ten aliases of level i - 1: 10^8 nodes once expanded, 80 lines of text.
  std::string text = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int i = 1; i <= 7; ++i) {
    std::string previous = "*a";
    previous.append(std::to_string(i - 1));
    text.append("a").append(std::to_string(i)).append(": &a").append(std::to_string(i)).append(" [").append(previous);
    for (int k = 1; k < 10; ++k) text.append(", ").append(previous);
    text.append("]\n");
  }
  EXPECT_THAT(error_of(text), HasSubstr("expands (through aliases) to more than 1000000 nodes"));
}

}  // namespace
}  // namespace thetad
