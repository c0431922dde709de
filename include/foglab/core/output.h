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
//
// Every temporary is registered while it exists: a command-line run that
// installs remove_temporaries_on_interrupt() removes them all on SIGINT,
// SIGTERM or SIGHUP and exits 128+signal. A folder of outputs
// (OutputFolder) is built in a temporary folder and put in place whole.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace foglab {

/// Throws UsageError "cannot write 'PATH': REASON" (an unwritable
/// destination is a problem with the arguments).
[[noreturn]] void cannot_write(const std::string& path, const std::string& reason);

/// Throws for a failed write, flush or close of `path` with the system's
/// `error_number`: DataError (exit 3) when the system could not store the
/// result — a full disk or quota (ENOSPC, EDQUOT), the file size limit
/// (EFBIG, `ulimit -f`), a reader that went away (EPIPE), a closed
/// descriptor (EBADF), an I/O error (EIO) — and UsageError (exit 2) for a
/// destination that cannot be written at all (permissions, a missing
/// folder).
[[noreturn]] void write_failed(const std::string& path, int error_number);

/// Where an output path leads (see above).
struct OutputTarget {
  std::string path;              ///< as given, for messages
  std::string file;              ///< the file written: links followed
  bool standard_output = false;  ///< "-"
  bool special = false;          ///< an existing non-regular file, written in place

  /// The temporary a regular target is written to first: ".NAME.tmpPID"
  /// beside `file`, so the final rename stays on one file system. A special
  /// target that must be written through a file (a MAT file to /dev/null)
  /// gets one in the temporary directory instead. The name is registered
  /// (register_temporary) before it is returned.
  std::string temporary() const;
};

/// Throws UsageError "cannot write 'PATH': ..." for an empty path or one
/// that names a directory.
OutputTarget output_target(const std::string& path);

/// Puts a finished temporary in place: renamed over a regular target,
/// copied into a special one (and removed), and forgotten. On failure the
/// temporary is removed and write_failed() names the path and the reason.
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

/// Records that `path` (a file, or a folder with everything in it) is an
/// unfinished output, to be removed if the run is interrupted.
void register_temporary(const std::string& path);

/// Removes a registered temporary (file or folder) and forgets it.
void discard_temporary(const std::string& path);

/// For a command-line program, called first in main() before any thread
/// starts: SIGINT, SIGTERM and SIGHUP are taken by one thread that removes
/// every registered temporary, says so on standard error and exits with
/// 128+signal; SIGXFSZ and SIGPIPE are ignored, so that a write beyond
/// `ulimit -f` or to a closed pipe fails (EFBIG, EPIPE) and takes the
/// normal error path. A temporary being put in place is finished first:
/// the signal waits for the rename (or a folder's whole swap).
void remove_temporaries_on_interrupt();

/// A folder of outputs (lab1, lab2, lab2-data --out) that appears whole or
/// not at all. The files are written into a temporary folder
/// ".NAME.tmpPID" beside the target; commit() renames it into place when
/// the target does not exist, or moves the files into an existing target
/// one by one (each replacing its old version) with interruptions held off
/// until all are moved. Destroyed without commit(), it removes what was
/// written and the target stays as it was.
class OutputFolder {
 public:
  /// Throws UsageError naming `option` when `path` is a file, or a folder
  /// cannot be created beside it.
  OutputFolder(std::string option, const std::string& path);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  /// Where the output `name` is written now (inside the temporary folder).
  std::string file(std::string_view name) const;
  /// Where the output `name` will be once committed, for messages.
  std::string final_file(std::string_view name) const;
  /// Puts the folder in place (see above).
  void commit();

 private:
  std::string option_;
  std::string path_;       // as given
  std::string target_;     // links followed
  std::string temporary_;  // empty once committed
};

}  // namespace foglab
