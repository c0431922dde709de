// foglab fuzz targets — shared plumbing: the input is written to a file of
// this process (the readers take paths), and only foglab's documented
// errors may come out of the code under test; anything else (another
// exception, a crash, a sanitizer report) is a finding.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "foglab/core/error.h"
#include "foglab/io/reader.h"

namespace foglab::fuzz {

/// Writes the input to /tmp/foglab_fuzz_<pid><suffix> and returns the path.
inline std::string input_file(const std::uint8_t* data, std::size_t size, const char* suffix) {
  const std::string path = "/tmp/foglab_fuzz_" + std::to_string(::getpid()) + suffix;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) throw std::runtime_error("fuzz: cannot write " + path);
  if (size > 0) std::fwrite(data, 1, size, f);
  std::fclose(f);
  return path;
}

/// Runs `body`; foglab's usage and data errors are the expected outcome of
/// a bad input (exit codes 2 and 3), so they are swallowed.
template <typename Body>
void expect_only_foglab_errors(Body&& body) {
  try {
    body();
  } catch (const UsageError&) {
  } catch (const DataError&) {
  }
}

/// Reads `path` as the CLI does: the channel list, then the series. Only
/// foglab's errors may come out, and a series that does come back must be
/// usable (samples and a positive rate); anything else traps.
inline void read_like_the_cli(const std::string& path, const io::ReadOptions& options) {
  expect_only_foglab_errors([&] {
    io::list_channels(path, options.format);
    const io::Series s = io::read_series(path, options);
    if (s.values.empty() || !(s.sample_rate_hz > 0.0)) __builtin_trap();
  });
}

}  // namespace foglab::fuzz
