// libFuzzer target: the MAT-file loading layer (the header sniffing of
// v4/v5/v7/v7.3 and matio/HDF5 behind it), through io::list_channels() and
// io::read_series() as the CLI calls them. The first byte chooses the
// variable asked for, the rest is the file.
#include <cstddef>
#include <cstdint>

#include "foglab/io/reader.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t mode = data[0];
  const std::string path = foglab::fuzz::input_file(data + 1, size - 1, ".mat");
  foglab::io::ReadOptions options;
  options.format = foglab::io::InputFormat::mat;
  static const char* const kChannels[] = {"", "Y1", "T1", "t"};
  options.channel = kChannels[mode & 3];
  if (mode & 4) options.sample_rate_hz = 10.0;
  foglab::fuzz::read_like_the_cli(path, options);
  return 0;
}
