// The demo's input scripts (demos/gui/script.h): a malformed line is refused
// with its file and line number, and a frame number says what is wrong with it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "script.h"

namespace {

std::string errorOf(const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / "test_demo_script.txt").string();
  std::ofstream(path) << text;
  try {
    demo::readScript(path);
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    return message.substr(message.find(':') + 1);  // without the path
  }
  return "accepted";
}

TEST(DemoScript, FrameNumbersOutOfRangeSaySo) {
  EXPECT_EQ(errorOf("99999999999999999999 key a\n"),
            "1: frame number 99999999999999999999 is out of range (at most 9223372036854775807)");
  EXPECT_EQ(errorOf("# comment\n\n-1 key a\n"), "3: expected a frame number >= 0 first, got '-1'");
  EXPECT_EQ(errorOf("key a\n"), "1: expected a frame number >= 0 first, got 'key'");
  EXPECT_EQ(errorOf("9223372036854775807 key a\n0 key b # comment\n"), "accepted");
}

}  // namespace
