// What the bad-input tests share (docs/architecture.md, Bad input): where a command writes,
// apart from where its streams are captured, and the shape of a refusal.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim::testing {

// Where commands write (`work`), apart from the captured streams and inputs (`scratch`), so
// that "nothing written" is `work.empty()`.
struct Dirs {
  TempDir scratch;
  TempDir work;
  std::filesystem::path at(const std::string& name) const { return work.path() / name; }
};

inline std::string entries_text(const TempDir& dir) {
  std::string s;
  for (const std::string& e : dir.entries()) s += " " + e;
  return s;
}

// Exit status 2, exactly one "tessim: error: ..." line holding every piece of `expected`,
// neither CLI11's own format nor a library prefix, nothing on stdout.
inline void expect_input_error(const TessimRun& r, const std::vector<std::string>& expected) {
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err.rfind("tessim: error: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.find("Run with --help"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("[json.exception"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  for (const std::string& piece : expected)
    EXPECT_NE(r.err.find(piece), std::string::npos) << "missing '" << piece << "' in: " << r.err;
}

}  // namespace tessim::testing
