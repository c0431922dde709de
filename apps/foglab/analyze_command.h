// foglab CLI — `foglab analyze`'s options and the parts its one-channel
// form (cmd_analyze.cc) shares with its IMU form (cmd_analyze_imu.cc).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "analysis_output.h"
#include "cli_common.h"
#include "foglab/io/reader.h"
#include "foglab/io/rosbag.h"
#include "foglab/model/analysis.h"
#include "foglab/report/report.h"

namespace foglab::cli {

struct AnalyzeCommand {
  InputOptions input;
  std::string channels;  ///< --channels: "gx,gy,..." or "all"; empty: --channel's one
  std::string topic;     ///< --topic of a ROS bag
  std::string temp_channel;
  std::string temp_degree = "auto";
  std::string taus = "octave";
  /// --max-missing-percent: the share of an Allan cluster's samples that may
  /// be missing across a gap (model::AnalysisOptions::max_missing_share, in %)
  double max_missing_percent = 1.0;
  std::string json_path;
  std::string csv_path;
  std::string report_path;
  std::string kalibr_path;
  std::string language = "en";  ///< --lang: the report's and the summary's (one gyroscope only)
};

struct Temperature {
  std::string channel;  ///< empty: none
  std::vector<double> values_c;
};

/// Reads the temperature that goes with `series` (or none, with a note
/// printed and added to `notes`).
Temperature load_temperature(const AnalyzeCommand& c, const io::Series& series,
                             std::vector<std::string>& notes);

/// UsageError for a --temp that cannot be read (no FILE, or a stream).
void check_temperature_option(const AnalyzeCommand& c);

/// The outputs checked against the input (never overwritten), the options
/// parsed, --temp checked: what both forms do before reading.
model::AnalysisOptions checked_analysis_options(const AnalyzeCommand& c);

/// model::AnalysisOptions::max_missing_share of a percentage given as
/// `option` (the CLI's --max-missing-percent, Python's max_missing_percent);
/// UsageError naming it outside [0, 10].
double max_missing_share_of(double percent, std::string_view option);

/// One channel analysed, and what its outputs need besides the analysis.
struct ChannelAnalysis {
  model::AnalysisResult result;
  AnalysisJsonInput json_input;
  report::ReportInput report_input;
};

/// `analyze`'s one-channel form on a loaded `series`: its temperature read
/// (when `read_temperature`; a ROS bag has none) and paired, the analysis,
/// and the inputs of the JSON and the report (with the record's preview
/// for the time plots when `preview`). Notes go through note().
ChannelAnalysis analyse_series(const AnalyzeCommand& c, io::Series series,
                               const model::AnalysisOptions& options, bool preview,
                               bool read_temperature);

/// Axis `name` (gx .. az, io::kImuChannels) of a ROS bag read whole, as
/// a Series in foglab's units (deg/h, m/s^2); its samples are moved out of
/// `record`. `rate_from_option`: --fs set the rate.
io::Series bag_axis_series(io::ImuRecord& record, const std::string& name, const std::string& path,
                           bool rate_from_option);

/// -1 for "auto", else 0..3 (UsageError otherwise).
int parse_temp_degree(const std::string& text);

/// The channels of the IMU form when `c` asks for it: several channels
/// (--channels, a ROS bag, or a file whose channel names say gyroscope and
/// accelerometer with no --channel), or an accelerometer's channel
/// (--units); none for the one-gyroscope form. A single channel the reader
/// is to choose is "".
std::optional<std::vector<std::string>> imu_channels(const AnalyzeCommand& c);

/// The IMU form on `channels` (imu_channels()): every channel analysed in
/// parallel, one JSON, one Markdown summary, one HTML report, Kalibr's
/// imu.yaml for both sensors.
void run_imu_analysis(const AnalyzeCommand& c, const std::vector<std::string>& channels);

}  // namespace foglab::cli
