#include "foglab/io/writer.h"

#include <fmt/format.h>
#include <matio.h>
#include <fcntl.h>
#include <unistd.h>

#include <cstdlib>
#include <new>

#include <bit>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <set>

#include "foglab/core/error.h"
#include "foglab/core/output.h"
#include "readers_internal.h"

namespace foglab::io {
namespace {

static_assert(std::endian::native == std::endian::little,
              "raw output assumes a little-endian host");

/// The target of a file output ("-" is refused: these formats go to files).
OutputTarget file_target(const std::string& path, std::string_view what) {
  OutputTarget t = output_target(path);
  if (t.standard_output) {
    cannot_write(path, fmt::format("a {} cannot go to standard output; give a file name", what));
  }
  return t;
}

bool valid_matlab_name(const std::string& name) {
  if (name.empty() || name.size() > 63) return false;
  if (std::isalpha(static_cast<unsigned char>(name[0])) == 0) return false;
  for (const char c : name) {
    if (std::isalnum(static_cast<unsigned char>(c)) == 0 && c != '_') return false;
  }
  return true;
}

std::string session_reason(const internal::MatioSession& session, const std::string& fallback) {
  const std::vector<std::string> messages = session.messages(false);
  return messages.empty() ? fallback : fallback + " (" + messages.front() + ")";
}

}  // namespace

void write_mat(const std::string& path, std::span<const NamedVector> variables) {
  std::set<std::string> names;
  for (const NamedVector& v : variables) {
    if (!valid_matlab_name(v.name)) {
      cannot_write(path, fmt::format("'{}' is not a valid MATLAB variable name", v.name));
    }
    if (!names.insert(v.name).second) {
      cannot_write(path, fmt::format("variable '{}' given twice", v.name));
    }
    if (v.values.empty()) cannot_write(path, fmt::format("variable '{}' is empty", v.name));
  }
  const OutputTarget target = file_target(path, "MAT file");
  const std::string tmp = target.temporary();
  internal::MatioSession session;
  errno = 0;
  mat_t* mat = Mat_CreateVer(tmp.c_str(), nullptr, MAT_FT_MAT5);
  if (mat == nullptr) {
    const int err = errno;
    discard_temporary(tmp);
    if (err != 0) write_failed(path, err);
    cannot_write(path, session_reason(session, "cannot create"));
  }
  // matio 1.5 does not check every fwrite(): a write cut short by a full
  // disk or `ulimit -f` can end in "success" with a truncated file. So the
  // system's word is taken from errno after each call, and the file's
  // layout is walked before it is put in place.
  bool ok = true;
  int storage_errno = 0;
  auto note_errno = [&storage_errno] {
    if (errno == ENOSPC || errno == EDQUOT || errno == EFBIG || errno == EIO) {
      storage_errno = errno;
    }
  };
  std::string reason;
  for (const NamedVector& v : variables) {
    size_t dims[2] = {v.values.size(), 1};
    // matio does not modify the data it writes; MAT_F_DONT_COPY_DATA keeps
    // it from copying (and freeing) our buffer.
    matvar_t* var = Mat_VarCreate(v.name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims,
                                  const_cast<double*>(v.values.data()), MAT_F_DONT_COPY_DATA);
    if (var == nullptr) {
      ok = false;
      reason = session_reason(session, fmt::format("cannot create variable '{}'", v.name));
      break;
    }
    errno = 0;
    const int status = Mat_VarWrite(mat, var, MAT_COMPRESSION_ZLIB);
    note_errno();
    Mat_VarFree(var);
    if (status != 0 || !session.messages(false).empty()) {
      ok = false;
      reason = session_reason(session, fmt::format("writing variable '{}' failed", v.name));
      break;
    }
  }
  errno = 0;
  const bool closed = Mat_Close(mat) == 0;
  note_errno();
  if (ok && !closed) {
    ok = false;
    reason = session_reason(session, "closing the file failed");
  }
  if (storage_errno != 0) ok = false;
  if (ok) {
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(tmp, ec);
    try {
      ok = !ec && internal::check_mat5_layout(tmp, size) == variables.size();
    } catch (const DataError&) {
      ok = false;
    }
    if (!ok) reason = "the file written is incomplete (the disk may be full)";
  }
  if (!ok) {
    discard_temporary(tmp);
    if (storage_errno != 0) write_failed(path, storage_errno);
    throw DataError(fmt::format("cannot write '{}': {}", path, reason));
  }
  commit_temporary(target, tmp);
}

void write_csv(const std::string& path, std::span<const NamedVector> columns,
               std::span<const std::string> comments) {
  if (columns.empty()) cannot_write(path, "no columns");
  const std::size_t rows = columns.front().values.size();
  for (const NamedVector& c : columns) {
    if (c.values.size() != rows) {
      cannot_write(path, fmt::format("column '{}' has {} values, '{}' has {}", c.name,
                                     c.values.size(), columns.front().name, rows));
    }
    if (c.name.find_first_of(",\n\"") != std::string::npos) {
      cannot_write(path, fmt::format("column name '{}' contains a comma, quote or newline",
                                     c.name));
    }
  }
  fmt::memory_buffer out;
  for (const std::string& line : comments) fmt::format_to(std::back_inserter(out), "# {}\n", line);
  for (std::size_t j = 0; j < columns.size(); ++j) {
    fmt::format_to(std::back_inserter(out), "{}{}", j ? "," : "", columns[j].name);
  }
  out.push_back('\n');
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t j = 0; j < columns.size(); ++j) {
      // {} is the shortest representation that reads back to the same double.
      fmt::format_to(std::back_inserter(out), "{}{}", j ? "," : "", columns[j].values[i]);
    }
    out.push_back('\n');
  }
  write_text_file(path, std::string_view(out.data(), out.size()));
}

std::string_view to_string(RawType type) { return type == RawType::f32 ? "f32" : "f64"; }

void write_raw(const std::string& path, std::span<const double> values, RawType type) {
  RawFileWriter writer(path, type);
  writer.append(values);
  writer.commit();
}

// Raw output goes through a page-aligned staging buffer written with
// O_DIRECT where the file system allows it: on virtual machines the page
// cache's first touch of fresh memory can limit buffered writes to about
// 200 MB/s, while direct writes sustain more than 1 GB/s (bench/RESULTS.md).
namespace {
constexpr std::size_t kStageBytes = std::size_t{8} << 20;  // multiple of the 4 KiB alignment
constexpr std::size_t kDirectAlign = 4096;
}  // namespace

RawFileWriter::RawFileWriter(const std::string& path, RawType type)
    : target_(file_target(path, "raw file")), type_(type) {
  // A device or a FIFO is written in place (no temporary); the buffer is
  // taken only once the file is open.
  if (target_.special) {
    fd_ = open_in_place(target_);
  } else {
    tmp_ = target_.temporary();
#ifdef O_DIRECT
    fd_ = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_DIRECT, 0644);
    direct_ = fd_ >= 0;
#endif
    if (fd_ < 0) fd_ = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd_ < 0) {
      const int err = errno;
      discard_temporary(tmp_);
      write_failed(path, err);
    }
  }
  void* memory = nullptr;
  if (posix_memalign(&memory, kDirectAlign, kStageBytes) != 0) {
    ::close(fd_);
    if (!tmp_.empty()) discard_temporary(tmp_);
    throw std::bad_alloc();
  }
  buffer_ = static_cast<unsigned char*>(memory);
}

RawFileWriter::~RawFileWriter() {
  if (fd_ >= 0) {
    ::close(fd_);
    if (!tmp_.empty()) discard_temporary(tmp_);
  }
  std::free(buffer_);
}

void RawFileWriter::fail(int error_number) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!tmp_.empty()) discard_temporary(tmp_);
  write_failed(target_.path, error_number);
}

// Writes the first `bytes` staged bytes and keeps the rest at the front.
void RawFileWriter::flush(std::size_t bytes) {
  std::size_t done = 0;
  while (done < bytes) {
    const ssize_t n = ::write(fd_, buffer_ + done, bytes - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(errno);
    }
    done += static_cast<std::size_t>(n);
  }
  std::memmove(buffer_, buffer_ + bytes, used_ - bytes);
  used_ -= bytes;
}

void RawFileWriter::append(std::span<const double> values) {
  if (fd_ < 0) cannot_write(target_.path, "the writer is closed");
  const std::size_t width = type_ == RawType::f32 ? 4 : 8;
  std::size_t i = 0;
  while (i < values.size()) {
    const std::size_t room = (kStageBytes - used_) / width;
    const std::size_t count = std::min(room, values.size() - i);
    unsigned char* out = buffer_ + used_;
    if (type_ == RawType::f32) {
      for (std::size_t k = 0; k < count; ++k) {
        const float v = static_cast<float>(values[i + k]);
        std::memcpy(out + 4 * k, &v, 4);
      }
    } else {
      std::memcpy(out, values.data() + i, count * 8);
    }
    used_ += count * width;
    i += count;
    if (kStageBytes - used_ < width) flush(used_ - used_ % kDirectAlign);
  }
  samples_ += values.size();
}

void RawFileWriter::commit() {
  if (fd_ < 0) cannot_write(target_.path, "the writer is closed");
  // Whole aligned blocks directly, then the tail through the page cache.
  flush(used_ - used_ % kDirectAlign);
#ifdef O_DIRECT
  if (direct_ && used_ > 0 && fcntl(fd_, F_SETFL, fcntl(fd_, F_GETFL) & ~O_DIRECT) != 0) {
    fail(errno);
  }
#endif
  flush(used_);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    const int err = errno;
    if (!tmp_.empty()) discard_temporary(tmp_);
    write_failed(target_.path, err);
  }
  if (!tmp_.empty()) commit_temporary(target_, tmp_);
}

}  // namespace foglab::io
