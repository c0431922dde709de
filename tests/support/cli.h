// Test support: run the foglab executable and capture its exit code and output.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/files.h"

namespace foglab::test {

struct CliRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

/// Runs `foglab ARGS` through the shell (ARGS is shell text; `stdin_text`,
/// if given, is piped to standard input).
inline CliRun run_foglab(const std::string& args, const std::string& stdin_text = "") {
  TempDir dir;
  const auto out = dir / "stdout";
  const auto err = dir / "stderr";
  std::string command = std::string("'") + FOGLAB_CLI_PATH + "' " + args;
  if (!stdin_text.empty()) {
    const auto in = dir / "stdin";
    std::ofstream(in) << stdin_text;
    command += " < '" + in.string() + "'";
  } else {
    command += " < /dev/null";
  }
  command += " > '" + out.string() + "' 2> '" + err.string() + "'";
  const int status = std::system(command.c_str());
  CliRun run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = read_file(out);
  run.err = read_file(err);
  return run;
}

inline std::string quote(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

}  // namespace foglab::test
