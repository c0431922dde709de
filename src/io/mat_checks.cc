// foglab — checks a MAT file's structure before matio reads it
// (readers_internal.h): each top-level element of a v4 or v5/v7 file lies
// inside the file, a v4 header does not claim more than the file holds, and
// a v7.3 (HDF5) file's metadata can be read without crashing the process.
// Each guards against a fuzzing finding (fuzz/regressions/mat_reader/).
#include <fcntl.h>
#include <fmt/format.h>
#include <matio.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "readers_internal.h"

namespace foglab::io::internal {

namespace {

// --- the layout walk: each top-level element must lie inside the file ---

bool read_at(std::FILE* file, std::uint64_t offset, unsigned char* out, std::size_t size) {
  if (offset > static_cast<std::uint64_t>(std::numeric_limits<off_t>::max())) return false;
  return fseeko(file, static_cast<off_t>(offset), SEEK_SET) == 0 &&
         std::fread(out, 1, size, file) == size;
}

std::uint32_t decode_u32(const unsigned char* bytes, bool little_endian) {
  return little_endian ? (std::uint32_t{bytes[0]} | std::uint32_t{bytes[1]} << 8 |
                          std::uint32_t{bytes[2]} << 16 | std::uint32_t{bytes[3]} << 24)
                       : (std::uint32_t{bytes[3]} | std::uint32_t{bytes[2]} << 8 |
                          std::uint32_t{bytes[1]} << 16 | std::uint32_t{bytes[0]} << 24);
}

[[noreturn]] void throw_truncated(const std::string& path, std::size_t index, std::uint64_t offset,
                                  double needed, std::uint64_t remaining) {
  throw_data_error(path, fmt::format("the MAT file is truncated: variable #{} (at byte {}) "
                                     "needs {} bytes, only {} remain",
                                     index, offset, needed, remaining));
}

// An uncompressed matrix element starts with three sub-elements, each
// "type, size, data": the array flags, the dimensions and the name. matio
// (1.5, mat5.c: Mat_VarReadNextInfo5) reads them as it finds them and
// allocates what they claim before reading it, so each claim is checked
// here against the element, read the way matio reads it:
// - the first 24 bytes are always the flags' tag, the flags (8 bytes) and
//   the dimensions' tag, in the long form;
// - dimensions of type int32 are size/4 numbers, allocated as 8 bytes each
//   (a 4 GB claim in a 56-byte element: an 8.5 GB allocation), and read
//   with 4 bytes of padding after an odd number of them (a size that is no
//   multiple of 4 moves the name: 3 bytes of dimensions put its tag where
//   the padding would be, and its 973 MB claim was found there);
// - the name's tag is the long form when its type word is exactly int8,
//   else the short one (up to 4 characters inside the tag);
// - a cell array or a function handle then allocates a pointer per
//   element, a structure one per element and field (after its field
//   names); each is at least a tag (8 bytes) of what follows in the
//   element.
// Fuzzing findings, fuzz/regressions/mat_reader/ (a 4 GB name in an
// 848-byte element, the dimensions above).
void check_mat5_matrix_header(const std::string& path, std::FILE* file, std::size_t index,
                              std::uint64_t offset, std::uint32_t bytes, bool little_endian) {
  const auto corrupt = [&](const std::string& what) {
    throw_data_error(path, fmt::format("the MAT file is corrupt: variable #{} (at byte {}) {}",
                                       index, offset, what));
  };
  const auto read_words = [&](std::uint64_t at, std::uint32_t* words, std::size_t count) {
    unsigned char raw[24];
    if (!read_at(file, offset + 8 + at, raw, 4 * count)) {
      throw_data_error(path, fmt::format("cannot read the MAT file at byte {}", offset + 8 + at));
    }
    for (std::size_t k = 0; k < count; ++k) words[k] = decode_u32(raw + 4 * k, little_endian);
  };
  const auto check_claim = [&](const char* part, std::uint64_t at, std::uint64_t claimed) {
    if (at + 8 + claimed > bytes) {
      corrupt(fmt::format("has {} claiming {} bytes where its {}-byte element has only {} left",
                          part, claimed, bytes, bytes - std::min<std::uint64_t>(bytes, at + 8)));
    }
  };
  if (bytes < 24) {
    corrupt(
        fmt::format("is a {}-byte matrix, shorter than the 24 bytes of its array flags and "
                    "dimensions tag",
                    bytes));
  }
  std::uint32_t head[6];  // flags tag (2 words), flags (2), dimensions tag (2)
  read_words(0, head, 6);
  const std::uint32_t matrix_class = head[2] & 0xffu;
  const bool has_pointers =
      matrix_class == MAT_C_CELL || matrix_class == MAT_C_STRUCT || matrix_class == MAT_C_FUNCTION;
  std::uint64_t at = 16;  // the dimensions' tag
  double elements = 1.0;
  if (head[4] == MAT_T_INT32) {
    const std::uint64_t dims_bytes = head[5];
    check_claim("dimensions", at, dims_bytes);
    // matio reads size/4 whole dimensions, and 4 bytes of padding after an
    // odd number of them (ReadRankDims), whatever the size says beyond that.
    const std::uint64_t rank = dims_bytes / 4;
    if (has_pointers) {
      for (std::uint64_t k = 0; k < 4 * rank; k += 4) {
        std::uint32_t dim = 0;
        read_words(at + 8 + k, &dim, 1);
        elements *= dim;
      }
    }
    at += 8 + (rank + 1) / 2 * 8;
  } else {
    at += 8;  // matio refuses dimensions of any other type
  }
  if (at + 8 > bytes) {  // matio would take the name's tag from what follows the element
    corrupt(fmt::format("ends at byte {} of {} of its element, before its name", at, bytes));
  }
  std::uint32_t name_tag[2];
  read_words(at, name_tag, 2);
  if (name_tag[0] == MAT_T_INT8) {
    check_claim("a name", at, name_tag[1]);
    at += 8 + (std::uint64_t{name_tag[1]} + 7) / 8 * 8;
  } else {
    at += 8;
  }
  // A structure's field names come first: a tag giving their length (type
  // int32, either form), then their characters (a long int8 tag; matio
  // allocates what it claims); a pointer per element and field follows.
  // Without fields nothing is allocated for the elements.
  double pointers_per_element = 1.0;
  if (matrix_class == MAT_C_STRUCT) {
    pointers_per_element = 0.0;
    if (at + 16 <= bytes) {
      std::uint32_t length_tag[2], names_tag[2];
      read_words(at, length_tag, 2);
      read_words(at + 8, names_tag, 2);
      if ((length_tag[0] & 0xffffu) == MAT_T_INT32 && length_tag[1] > 0 &&
          names_tag[0] == MAT_T_INT8) {
        check_claim("field names", at + 8, names_tag[1]);
        pointers_per_element = std::floor(static_cast<double>(names_tag[1]) / length_tag[1]);
        at += 16 + (std::uint64_t{names_tag[1]} + 7) / 8 * 8;
      }
    }
  }
  if (has_pointers) {
    // Each element (or field of one) is at least a tag of what follows.
    const double rest = at < bytes ? static_cast<double>(bytes - at) : 0.0;
    const double parts = elements * pointers_per_element;
    if (parts * 8.0 > rest) {
      const std::string what =
          matrix_class == MAT_C_CELL ? fmt::format("{} cells", elements)
          : matrix_class == MAT_C_STRUCT
              ? fmt::format("{} elements of {} fields", elements, pointers_per_element)
              : fmt::format("{} function handles", elements);
      corrupt(
          fmt::format("claims {} in the {} bytes left of its element, which can hold at "
                      "most {}",
                      what, rest, std::floor(rest / 8.0)));
    }
  }
}

// The bytes a v4 variable occupies (its 20-byte header "type, mrows, ncols,
// imagf, namlen", the name and the data), or nothing when the header is no
// valid v4 header in that byte order (type = 1000 M + 100 O + 10 P + T).
std::optional<double> mat4_variable_bytes(const unsigned char* header, bool little_endian) {
  constexpr std::array<int, 6> kElementBytes = {8, 4, 4, 2, 2, 1};
  std::array<std::uint32_t, 5> field{};
  for (std::size_t k = 0; k < field.size(); ++k) {
    field[k] = decode_u32(header + 4 * k, little_endian);
  }
  const std::uint32_t type = field[0];
  if (!(type < 5000 && (type / 100) % 10 == 0 && (type / 10) % 10 <= 5 && type % 10 <= 2)) {
    return std::nullopt;
  }
  return 20.0 + field[4] +
         static_cast<double>(field[1]) * field[2] * kElementBytes[(type / 10) % 10] *
             (field[3] != 0 ? 2 : 1);
}

// The byte order matio 1.5 reads a v4 header in (mat4.c,
// Mat_VarReadNextInfo4): the type word read in this machine's order
// (little-endian), swapped when that is outside 0-4052; then the type's
// thousands digit M, 0 for little-endian and 1 for big-endian, orders the
// rest. Nothing when matio would find no v4 header there.
std::optional<bool> mat4_little_endian(const unsigned char* header) {
  auto type = static_cast<std::int32_t>(decode_u32(header, true));
  if (type < 0 || type > 4052) type = static_cast<std::int32_t>(decode_u32(header, false));
  if (type < 0 || type > 4052 || type / 1000 > 1) return std::nullopt;
  return type / 1000 == 0;
}

// The bytes of a v4 variable in the byte order matio reads it in: the
// whole variable when its type is valid there, else the header and the
// name (which matio allocates first whatever the type says); nothing when
// matio would find no v4 header.
std::optional<double> mat4_claimed_bytes(const unsigned char* header) {
  const std::optional<bool> little_endian = mat4_little_endian(header);
  if (!little_endian) return std::nullopt;
  if (const std::optional<double> whole = mat4_variable_bytes(header, *little_endian)) return whole;
  return 20.0 + decode_u32(header + 16, *little_endian);
}

}  // namespace

// v5/v7: a 128-byte header, then elements "type (4 bytes), size (4 bytes),
// data" of type matrix (14) or compressed matrix (15).
std::size_t check_mat5_layout(const std::string& path, std::uint64_t size) {
  FilePtr file(std::fopen(path.c_str(), "rb"));
  unsigned char header[128];
  if (!file || size < 128 || !read_at(file.get(), 0, header, sizeof(header))) {
    throw_data_error(path, "the MAT file is truncated inside its 128-byte header");
  }
  // MATLAB writes the characters "MI" as one 16-bit number.
  const bool little_endian = header[126] == 'I' && header[127] == 'M';
  std::uint64_t offset = 128;
  std::size_t index = 0;
  while (size - offset >= 8) {
    unsigned char tag[8];
    if (!read_at(file.get(), offset, tag, sizeof(tag))) {
      throw_data_error(path, fmt::format("cannot read the MAT file at byte {}", offset));
    }
    ++index;
    const std::uint32_t type = decode_u32(tag, little_endian);
    const std::uint32_t bytes = decode_u32(tag + 4, little_endian);
    if (type != MAT_T_MATRIX && type != MAT_T_COMPRESSED) {
      throw_data_error(path, fmt::format("the MAT file is corrupt: variable #{} (at byte {}) "
                                         "has element type {}, expected 14 (matrix) or 15 "
                                         "(compressed)",
                                         index, offset, type));
    }
    if (bytes > size - offset - 8) {
      throw_truncated(path, index, offset, 8.0 + bytes, size - offset);
    }
    if (type == MAT_T_MATRIX)
      check_mat5_matrix_header(path, file.get(), index, offset, bytes, little_endian);
    offset += 8 + std::uint64_t{bytes};
  }
  // Fewer than 8 bytes left: the start of a cut variable's tag (zeros are
  // tolerated as padding).
  if (offset < size) {
    unsigned char rest[8] = {};
    const auto count = static_cast<std::size_t>(size - offset);
    if (!read_at(file.get(), offset, rest, count)) {
      throw_data_error(path, fmt::format("cannot read the MAT file at byte {}", offset));
    }
    if (std::any_of(rest, rest + count, [](unsigned char b) { return b != 0; })) {
      throw_truncated(path, index + 1, offset, 8.0, count);
    }
  }
  return index;
}

// v4: per variable a 20-byte header "type, mrows, ncols, imagf, namlen"
// (type = 1000 M + 100 O + 10 P + T), the name, then the data.
void check_mat4_layout(const std::string& path, std::uint64_t size) {
  FilePtr file(std::fopen(path.c_str(), "rb"));
  if (!file) throw_data_error(path, "cannot reopen the MAT file");
  std::uint64_t offset = 0;
  std::size_t index = 0;
  while (offset < size) {
    ++index;
    unsigned char header[20];
    if (size - offset < sizeof(header) || !read_at(file.get(), offset, header, sizeof(header))) {
      throw_truncated(path, index, offset, sizeof(header), size - offset);
    }
    const std::optional<bool> little_endian = mat4_little_endian(header);
    const std::optional<double> bytes =
        little_endian ? mat4_variable_bytes(header, *little_endian) : std::nullopt;
    if (!bytes) {
      throw_data_error(path, fmt::format("the MAT file is corrupt: variable #{} (at byte {}) has "
                                         "no valid v4 header",
                                         index, offset));
    }
    const double needed = *bytes;
    if (needed > static_cast<double>(size - offset)) {
      throw_truncated(path, index, offset, needed, size - offset);
    }
    offset += static_cast<std::uint64_t>(needed);
  }
}

// --- HDF5 files that are not MAT files ---

// HDF5 (1.10, H5F__super_read) reads a version 0 or 1 superblock's driver
// information block, when its address is defined, as 16 bytes of header
// and the size its header claims, allocating that size and filling what
// lies beyond the end of the file with zeros: a 3.7 kB file whose block
// claimed 4 GB took 4.2 GB of memory and 7 s (twice: in the probe's child
// and again in the process; a fuzzing finding, fuzz/regressions/mat_reader/).
// The superblock (HDF5 File Format Specification, "Version 0 and 1 Superblock";
// little-endian): the signature (8 bytes), four version bytes, a reserved
// byte, the sizes of offsets and of lengths (1 byte each), a reserved byte,
// two 2-byte K values, 4 bytes of flags, in version 1 four more bytes, then
// the base address, the free-space address, the end-of-file address and
// the driver information block's address, each an offset. The block:
// version (1 byte), 3 reserved, its information size (4 bytes), the
// driver's name (8 bytes), then the information. Addresses are relative to
// the base address.
void check_hdf5_driver_block(const std::string& path, std::uint64_t size,
                             std::uint64_t signature_at) {
  FilePtr file(std::fopen(path.c_str(), "rb"));
  unsigned char head[64] = {};
  if (!file || signature_at + sizeof(head) > size ||
      !read_at(file.get(), signature_at, head, sizeof(head))) {
    return;  // HDF5 reports a superblock cut short
  }
  const unsigned version = head[8];
  const unsigned offset_bytes = head[13];
  if (version > 1 || offset_bytes != 8) return;  // MATLAB and matio write 8-byte offsets
  const auto u64 = [](const unsigned char* b) {
    return std::uint64_t{decode_u32(b, true)} | std::uint64_t{decode_u32(b + 4, true)} << 32;
  };
  const std::size_t addresses = version == 0 ? 24 : 28;  // the base address
  const std::uint64_t base = u64(head + addresses);
  const std::uint64_t driver = u64(head + addresses + 24);
  if (driver == ~std::uint64_t{0}) return;  // undefined: no driver block
  const double block_at = static_cast<double>(base) + static_cast<double>(driver);
  unsigned char block[8];
  const auto claim = [&]() -> double {
    if (block_at + 16.0 > static_cast<double>(size) ||
        !read_at(file.get(), static_cast<std::uint64_t>(block_at), block, sizeof(block))) {
      return 16.0;
    }
    return 16.0 + decode_u32(block + 4, true);
  }();
  if (block_at + claim > static_cast<double>(size)) {
    throw_data_error(path, fmt::format("the MAT file (v7.3, HDF5) is damaged: its driver "
                                       "information block at byte {} claims {} bytes, more "
                                       "than the {}-byte file holds",
                                       block_at, claim, size));
  }
}

// The offset of an HDF5 superblock signature (HDF5 looks at 0, 512, 1024,
// 2048, ...; a v7.3 MAT file has it at 512, after MATLAB's header), or
// nullopt.
// HDF5 (1.10, Debian 12) can crash (SIGSEGV in H5F__accum_read under
// H5Gget_info, from Mat_Open()) on a damaged v7.3 file — a fuzzing finding,
// fuzz/regressions/mat_reader/. A library crash must not take foglab down
// without a word, so a v7.3 file is first opened, and its variables' headers
// read, in a child process; when the child dies of a signal the file is
// reported as damaged. (Only the metadata is probed; reading one file's
// headers twice costs milliseconds.)
void probe_mat73_in_child(const std::string& path) {
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) return;  // no process to spare: read it directly
  if (pid == 0) {
    const int devnull = ::open("/dev/null", O_WRONLY);
    if (devnull >= 0) {
      ::dup2(devnull, STDOUT_FILENO);
      ::dup2(devnull, STDERR_FILENO);
    }
    if (mat_t* mat = Mat_Open(path.c_str(), MAT_ACC_RDONLY)) {
      while (matvar_t* var = Mat_VarReadNextInfo(mat)) Mat_VarFree(var);
      Mat_Close(mat);
    }
    ::_exit(0);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status)) {
    throw_data_error(path, fmt::format("the MAT file (v7.3, HDF5) is damaged: the HDF5 library "
                                       "crashed reading its structure ({})",
                                       ::strsignal(WTERMSIG(status))));
  }
}

// Before matio sees a file without v5's header marks ("IM"/"MI" at bytes
// 126-127): when its first 20 bytes, read in the byte order matio reads
// them in, claim more bytes (name and data) than the file holds, it is
// refused here — Mat_Open() would otherwise allocate the claimed name
// length (up to 4 GB) while trying v4 (fuzzing findings,
// fuzz/regressions/mat_reader/: a 1.8 GB name; a 1.7 GB one in a header
// whose other byte order claims 122 bytes, which the check had taken).
void check_mat4_first_header(const std::string& path, std::uint64_t size) {
  FilePtr file(std::fopen(path.c_str(), "rb"));
  unsigned char header[128] = {};
  if (!file || !read_at(file.get(), 0, header, std::min<std::uint64_t>(size, sizeof(header)))) {
    return;  // Mat_Open() reports unreadable files
  }
  if (size >= 128 &&
      ((header[126] == 'I' && header[127] == 'M') || (header[126] == 'M' && header[127] == 'I'))) {
    return;  // v5, v7 or v7.3: checked after opening
  }
  if (size < 20) return;
  const std::optional<double> need = mat4_claimed_bytes(header);
  if (need && *need > static_cast<double>(size)) throw_truncated(path, 1, 0, *need, size);
}

std::optional<std::uint64_t> hdf5_signature_offset(const std::string& path, std::uint64_t size) {
  static constexpr unsigned char kSignature[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
  FilePtr file(std::fopen(path.c_str(), "rb"));
  if (!file) return std::nullopt;
  for (std::uint64_t offset = 0; offset + sizeof(kSignature) <= size;
       offset = offset == 0 ? 512 : offset * 2) {
    unsigned char bytes[sizeof(kSignature)];
    if (!read_at(file.get(), offset, bytes, sizeof(bytes))) return std::nullopt;
    if (std::memcmp(bytes, kSignature, sizeof(kSignature)) == 0) return offset;
  }
  return std::nullopt;
}

}  // namespace foglab::io::internal
