// Test support: run the foglab executable and capture its exit code and output.
#pragma once

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

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

/// Runs `foglab ARGS` that prints JSON on standard output, and parses it: a failed
/// run is a test failure (with ARGS and the error), and an empty object.
inline nlohmann::json run_json(const std::string& args) {
  const CliRun r = run_foglab(args);
  EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
  if (r.exit_code != 0) return nlohmann::json::object();
  return nlohmann::json::parse(r.out);
}

inline std::string quote(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

/// The names below `dir` that are foglab temporaries (".NAME.tmpPID").
inline std::vector<std::string> temporaries(const std::filesystem::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.find(".tmp") != std::string::npos) found.push_back(e.path().string());
  }
  return found;
}

/// AddressSanitizer reserves terabytes of address space for its shadow: an
/// address-space limit (`ulimit -v`) cannot be tested under it.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kUnderAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kUnderAddressSanitizer = true;
#else
inline constexpr bool kUnderAddressSanitizer = false;
#endif
#else
inline constexpr bool kUnderAddressSanitizer = false;
#endif

/// Starts `foglab ARGS` in the background; its standard error goes to `err`.
inline pid_t start_foglab(const std::string& args, const std::filesystem::path& err) {
  const std::string command = std::string("exec '") + FOGLAB_CLI_PATH + "' " + args +
                              " < /dev/null > /dev/null 2> " + quote(err);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

/// Its exit code (128 + signal when killed).
inline int wait_for(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/// Polls (1 ms) until `ready` holds or the process ends (left for
/// wait_for() to collect); true when it held.
template <typename Ready>
bool wait_until(pid_t pid, Ready ready) {
  for (int i = 0; i < 60000; ++i) {
    if (ready()) return true;
    siginfo_t info{};
    if (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 &&
        info.si_pid == pid) {
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

}  // namespace foglab::test
