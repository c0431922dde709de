// Test support for the io readers: a temporary directory to write inputs in.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "foglab/io/reader.h"
#include "support/files.h"

namespace foglab::io {

class ReaderTest : public ::testing::Test {
 protected:
  /// Writes `bytes` to `name` in the test's directory; returns its path.
  std::string write(const std::string& name, const std::string& bytes) {
    const std::string path = dir_.file(name);
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
  static ReadOptions with_fs(double rate_hz) {
    ReadOptions options;
    options.sample_rate_hz = rate_hz;
    return options;
  }
  test::TempDir dir_;
};

}  // namespace foglab::io
