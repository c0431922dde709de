// foglab CLI — `foglab batch` as functions, for the command (cmd_batch.cc) and for the
// Python package (foglab.batch, and foglab.dask, which analyses each file on a Dask worker
// with batch_file_units() and writes the report with run_batch()).
#pragma once

#include <string>
#include <vector>

#include "analyze_command.h"
#include "foglab/model/analysis.h"
#include "foglab/model/fleet.h"

namespace foglab::cli {

struct BatchCommand {
  std::vector<std::string> inputs;
  std::string out;
  AnalyzeCommand analyze;  ///< the reading and analysis options; input.path set per file
  unsigned workers = 0;    ///< 0: one per core
  double outlier_z = 3.5;
  bool redo = false;
  bool no_plots = false;
};

/// A recording of a batch and the name its units take.
struct BatchFile {
  std::string path;
  std::string name;  ///< the file's stem; the folder in front where two stems are equal
};

/// INPUTS (files, folders, quoted globs) as files, each once, with their names. Throws
/// UsageError for an input that is missing, a stream, or a folder without recordings.
std::vector<BatchFile> batch_files(const std::vector<std::string>& inputs);

/// The batch's analysis options, checked (UsageError), `first_file` named in messages.
model::AnalysisOptions batch_analysis_options(const BatchCommand& c, const std::string& first_file);

/// One unit of a file: analysed, kept from an earlier run, or failed.
struct UnitOutcome {
  std::string name;     ///< "unit_007", "imu1.gyro_x"
  std::string channel;  ///< as read ("" before, when the reader chose)
  std::string json;     ///< analysed with no units folder: the `analyze --json` document
  bool kept = false;    ///< its JSON in the units folder stands (same file, same options)
  std::string input;    ///< "FILE" or "FILE channel C", for messages
  std::string error;    ///< failed: the message
  int exit_code = 0;    ///< failed: `analyze`'s (2 usage, 3 data, 1 internal)
};

/// The units of `file`, analysed one after the other in the calling thread (the reader's
/// and analysis's notes go into each JSON, not to the terminal). With `units_dir`, a unit
/// whose result is there from an earlier run is kept (unless c.redo) and each analysed
/// unit's JSON is written there whole as soon as it is done; with "" nothing is read or
/// written. Never throws for a record that fails: its outcome says why.
std::vector<UnitOutcome> batch_file_units(const BatchCommand& c, const BatchFile& file,
                                          const model::AnalysisOptions& options,
                                          const std::string& units_dir);

/// Whether every unit of `file` has its result in `units_dir` from an earlier run that
/// stands for it (the same file, not modified since, the same channel and options): what
/// batch_file_units() keeps.
bool batch_file_kept(const BatchCommand& c, const BatchFile& file, const std::string& units_dir);

/// What a batch did.
struct BatchSummary {
  std::size_t files = 0;
  std::size_t units = 0;  ///< in the report
  std::size_t analysed = 0, kept = 0;
  std::vector<UnitOutcome> failures;
  std::vector<model::FleetOutlier> outliers;
  std::string fleet_json;  ///< the text of OUT/fleet.json
};

/// The whole batch: the files analysed in parallel (model::run_work_queue, c.workers at
/// once), OUT/units/NAME.json for each unit, then OUT/fleet.{md,csv,html,json}. A record
/// that fails is in the summary (and the report), not thrown; UsageError for bad options.
BatchSummary run_batch(const BatchCommand& c);

}  // namespace foglab::cli
