// libFuzzer target: the text reader (CSV/TSV/whitespace, header, comments,
// columns by name or index, time column), through io::read_series() as the
// CLI calls it. The first byte chooses the options, the rest is the file.
#include <cstddef>
#include <cstdint>

#include "foglab/io/reader.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t mode = data[0];
  const std::string path = foglab::fuzz::input_file(data + 1, size - 1, ".csv");
  foglab::io::ReadOptions options;
  options.format = foglab::io::InputFormat::text;
  // Bits 0-1: the channel; bit 2: a sample rate or the time column; bit 3: units.
  static const char* const kChannels[] = {"", "rate", "2", "Y1"};
  options.channel = kChannels[mode & 3];
  if (mode & 4) options.sample_rate_hz = 10.0;
  if (mode & 8) options.unit = foglab::RateUnit::deg_per_second;
  foglab::fuzz::read_like_the_cli(path, options);
  return 0;
}
