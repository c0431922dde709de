// foglab — raw little-endian IEEE float32 / float64 samples, one channel.
//
// A raw file is nothing but the samples, so it carries no sample rate (one
// must be given) and no names (its one channel is called "1"). It is read in
// blocks; a size that is not a whole number of samples is a truncated file.
#include <fmt/format.h>

#include <bit>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "readers_internal.h"

namespace foglab::io::internal {
namespace {

template <typename Bits>
Bits from_little_endian(const unsigned char* bytes) {
  Bits bits;
  std::memcpy(&bits, bytes, sizeof(bits));
  if constexpr (std::endian::native == std::endian::big) {
    Bits swapped = 0;
    for (std::size_t k = 0; k < sizeof(Bits); ++k) {
      swapped = static_cast<Bits>(swapped << 8) | static_cast<Bits>(bits & 0xff);
      bits = static_cast<Bits>(bits >> 8);
    }
    bits = swapped;
  }
  return bits;
}

double decode(const unsigned char* bytes, std::size_t element_bytes) {
  if (element_bytes == 4) {
    return static_cast<double>(std::bit_cast<float>(from_little_endian<std::uint32_t>(bytes)));
  }
  return std::bit_cast<double>(from_little_endian<std::uint64_t>(bytes));
}

[[noreturn]] void throw_truncated(const std::string& path, std::uint64_t bytes,
                                  std::size_t element_bytes) {
  throw_data_error(path, fmt::format("truncated: {} bytes is not a multiple of {} (the size of "
                                     "one float{} sample)",
                                     bytes, element_bytes, element_bytes * 8));
}

}  // namespace

Series read_raw(const std::string& path, const ReadOptions& options, InputFormat format) {
  const std::size_t element_bytes = format == InputFormat::f32 ? 4 : 8;
  if (!options.sample_rate_hz) {
    throw UsageError(fmt::format(
        "{}: raw input has no sample rate: give ReadOptions::sample_rate_hz", quoted_path(path)));
  }
  if (!options.time_channel.empty()) {
    throw UsageError(fmt::format("{}: raw input has no time column (got time channel '{}')",
                                 quoted_path(path), options.time_channel));
  }
  if (!options.channel.empty() && options.channel != "1") {
    throw_data_error(
        path, fmt::format("no channel '{}': a raw file has one channel, '1'", options.channel));
  }

  Series series;
  series.path = path;
  series.channel = std::string(1, '1');
  series.available_channels = {series.channel};
  series.variables = series.available_channels;

  std::FILE* file = stdin;
  FilePtr owned;
  if (path != "-") {
    owned.reset(std::fopen(path.c_str(), "rb"));
    if (!owned) {
      throw UsageError(fmt::format("cannot open '{}': {}", path, std::strerror(errno)));
    }
    file = owned.get();
  }
  // A regular file's size is checked before reading; a stream's at its end.
  if (const std::optional<std::uint64_t> size = regular_file_size(path)) {
    if (*size == 0) throw_data_error(path, "the file is empty (no samples)");
    if (*size % element_bytes != 0) throw_truncated(path, *size, element_bytes);
    // One spare element for the in-place angle integration (allan.h).
    series.values.reserve(static_cast<std::size_t>(*size / element_bytes) + 1);
    advise_huge_pages(series.values.data(), series.values.capacity());
  }

  // Blocks of whole samples; a partial sample at the end of a block waits
  // for the next one.
  std::vector<unsigned char> block(std::size_t{1} << 20);
  std::size_t carried = 0;
  std::uint64_t total = 0;
  while (true) {
    const std::size_t got = std::fread(block.data() + carried, 1, block.size() - carried, file);
    if (got == 0) {
      if (std::ferror(file)) {
        throw_data_error(path, fmt::format("read error: {}", std::strerror(errno)));
      }
      break;
    }
    total += got;
    const std::size_t available = carried + got;
    const std::size_t whole = available / element_bytes;
    if (options.max_samples && series.values.size() + whole > *options.max_samples) {
      throw_data_error(path, fmt::format("more than {} samples: the limit for one record "
                                         "(ReadOptions::max_samples)",
                                         *options.max_samples));
    }
    for (std::size_t i = 0; i < whole; ++i) {
      series.values.push_back(decode(block.data() + i * element_bytes, element_bytes));
    }
    carried = available - whole * element_bytes;
    std::memmove(block.data(), block.data() + whole * element_bytes, carried);
  }
  if (total == 0) throw_data_error(path, "the file is empty (no samples)");
  if (carried != 0) throw_truncated(path, total, element_bytes);
  return series;
}

}  // namespace foglab::io::internal
