// Runs the tessim binary as a user does, capturing its exit status, stdout and stderr.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace tessim::testing {

struct TessimRun {
  int status = -1;
  std::string out, err;
};

inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// `scratch` holds the captured streams (removed afterwards).
inline TessimRun run_tessim(const std::vector<std::string>& args, const std::filesystem::path& scratch) {
  std::string command = shell_quote(TESSIM_BINARY);
  for (const std::string& a : args) {
    command += ' ';  // not " " + ...: GCC 12 misreports that as an overlapping copy (-Wrestrict)
    command += shell_quote(a);
  }
  const auto out = scratch / "stdout.txt", err = scratch / "stderr.txt";
  command += " >" + shell_quote(out.string()) + " 2>" + shell_quote(err.string());
  const int raw = std::system(command.c_str());
  auto slurp = [](const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  TessimRun r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

}  // namespace tessim::testing
