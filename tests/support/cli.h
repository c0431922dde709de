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

namespace foglab::test {

struct CliRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A fresh temporary directory, removed with the object.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "foglab_test_XXXXXX").string();
    path_ = mkdtemp(pattern.data());
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
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
