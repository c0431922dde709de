// foglab — writing records: MAT v5 files, CSV tables, raw binary.
//
// Every writer is atomic: the data go to a temporary file in the target's
// directory (".NAME.tmpPID"), which is renamed over the target only once it
// is complete and closed. On any failure the temporary is removed and the
// target is left as it was (absent or the old file) — never half written.
// Links are followed, and a target that is not a regular file (/dev/null,
// a FIFO) is written in place (core/output.h).
// Errors are "cannot write 'PATH': reason" (core/output.h write_failed()):
// a UsageError (exit 2) for an unwritable destination, a DataError (exit 3)
// when the system could not store the result (a full disk, `ulimit -f`).
//
// MAT files are MATLAB 5 level files (what MATLAB `save -v7` and Octave
// `save -mat` write) with zlib-compressed variables, loadable by MATLAB,
// Octave, SciPy and foglab's own reader. Each variable is a real double
// column vector N x 1; a one-element variable is a 1 x 1 scalar (the lab's
// sample rate `f`).
#pragma once

#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "foglab/core/output.h"

namespace foglab::io {

/// A named double vector to write (not owned: the span must outlive the call).
struct NamedVector {
  std::string name;               ///< MAT variable name / CSV column header
  std::span<const double> values;
};

/// Writes a MAT v5 file holding `variables`, in order, each N x 1 (1 x 1
/// for one value). Names must be valid MATLAB identifiers and unique;
/// vectors must be non-empty. Throws UsageError naming the path otherwise
/// or when the file cannot be written.
void write_mat(const std::string& path, std::span<const NamedVector> variables);

/// Writes a CSV table: optional `# ` comment lines (e.g. units), a header
/// line of the column names, then one row per sample, every value in the
/// shortest form that reads back to the same double. All columns must have
/// the same length. `path` "-" writes to standard output.
void write_csv(const std::string& path, std::span<const NamedVector> columns,
               std::span<const std::string> comments = {});

/// Sample type of a raw binary file.
enum class RawType {
  f32,  ///< little-endian IEEE float32
  f64,  ///< little-endian IEEE float64
};

/// "f32" / "f64".
std::string_view to_string(RawType type);

/// Writes `values` as raw little-endian samples (no header).
void write_raw(const std::string& path, std::span<const double> values, RawType type);

/// A raw file written piece by piece in constant memory, still atomically:
/// append() blocks, then commit(). Destroying the writer without commit()
/// (an exception on the way) removes the temporary and leaves no file.
class RawFileWriter {
 public:
  RawFileWriter(const std::string& path, RawType type);
  ~RawFileWriter();
  RawFileWriter(const RawFileWriter&) = delete;
  RawFileWriter& operator=(const RawFileWriter&) = delete;

  void append(std::span<const double> values);
  /// Closes and renames into place; throws as write_failed() on failure.
  void commit();
  std::uint64_t samples() const { return samples_; }

 private:
  void fail(int error_number);
  void flush(std::size_t bytes);

  OutputTarget target_;
  std::string tmp_;  // the temporary; empty when written in place
  RawType type_;
  int fd_ = -1;
  bool direct_ = false;   // the file was opened with O_DIRECT (page cache bypassed)
  std::uint64_t samples_ = 0;
  unsigned char* buffer_ = nullptr;  // page-aligned staging buffer
  std::size_t used_ = 0;             // bytes staged
};

}  // namespace foglab::io
