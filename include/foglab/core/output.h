// foglab — writing result files without ever leaving a half-written one,
// and without destroying what an output path leads to.
//
// An output path is one of:
// - "-": standard output, for at most one output of a run; every write and
//   the final flush are checked (a full disk or a closed stream is an error);
// - a regular file or a name not yet taken: written to a temporary
//   ".NAME.tmpPID" beside the file and renamed over it once complete, so the
//   old file stays until the new one is whole. Symbolic links are followed
//   first: the file a link points to is replaced and the link kept;
// - an existing file that is not a regular one (a character device such as
//   /dev/null, a FIFO, /dev/stdout): written in place, never renamed over
//   (renaming a temporary over /dev/null had replaced the device node).
// Before anything is computed, check_outputs() refuses an output that is an
// input of the same run or another of its outputs.
#pragma once

#include <span>
#include <string>
#include <string_view>

namespace foglab {

/// Throws UsageError "cannot write 'PATH': REASON" (an unwritable
/// destination is a problem with the arguments).
[[noreturn]] void cannot_write(const std::string& path, const std::string& reason);

/// Where an output path leads (see above).
struct OutputTarget {
  std::string path;              ///< as given, for messages
  std::string file;              ///< the file written: links followed
  bool standard_output = false;  ///< "-"
  bool special = false;          ///< an existing non-regular file, written in place

  /// The temporary a regular target is written to first: ".NAME.tmpPID"
  /// beside `file`, so the final rename stays on one file system. A special
  /// target that must be written through a file (a MAT file to /dev/null)
  /// gets one in the temporary directory instead.
  std::string temporary() const;
};

/// Throws UsageError "cannot write 'PATH': ..." for an empty path or one
/// that names a directory.
OutputTarget output_target(const std::string& path);

/// Puts a finished temporary in place: renamed over a regular target,
/// copied into a special one (and removed). On failure the temporary is
/// removed and UsageError names the path and the system's reason.
void commit_temporary(const OutputTarget& target, const std::string& temporary);

/// Opens a special target for writing in place (never created or
/// truncated; a regular file behind /dev/stdout is appended to). Throws
/// UsageError naming the path.
int open_in_place(const OutputTarget& target);

/// Writes `content` to `path` as above. Throws UsageError when the file
/// cannot be written, DataError when standard output cannot.
void write_text_file(const std::string& path, std::string_view content);

/// An input or output path of a run with the option that gave it, for
/// messages ("--json", "FILE").
struct RunPath {
  std::string_view option;
  std::string path;
};

/// Refuses, with a UsageError naming both options, an output that is one of
/// the run's inputs or another of its outputs: the same file (device and
/// inode, links followed) or, for files not yet there, the same path once
/// made absolute and normal; "-" as two outputs. Empty paths and "-" as an
/// input (standard input) are skipped; character devices (/dev/null, a
/// terminal) may take several outputs.
void check_outputs(std::span<const RunPath> inputs, std::span<const RunPath> outputs);

/// Flushes standard output and throws DataError when anything written to it
/// was lost (a full disk, a closed stream); called once at the end of a run.
void finish_standard_output();

}  // namespace foglab
