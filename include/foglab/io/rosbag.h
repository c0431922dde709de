// foglab — IMU records in ROS 1 bags: sensor_msgs/Imu messages, read and written through the
// ROS library rosbag_storage (no bag parser of our own).
//
// A bag holds topics, each a stream of messages of one type. read_imu_bag() reads one topic of
// sensor_msgs/Imu messages into six channels: the angular velocity [rad/s] and the linear
// acceleration [m/s^2], x, y, z as in the bag (ROS REP 103/145 units; the orientation and the
// covariances are not read). A bag without an index (a recording cut short: the recorder writes
// the index when it closes the bag), a truncated or damaged bag, compressed chunks (bz2, lz4)
// are all handled by the library; what it refuses is a DataError naming the file.
//
// Time. A sensor samples on a uniform clock, but the stamps a ROS driver puts in header.stamp
// carry the host's scheduling jitter, and a busy host drops messages. The reader therefore puts
// every message on a uniform grid and reports what the stamps say (StampTiming):
//   * the times are header.stamp; when every header stamp is zero (a driver that leaves them
//     unset), the bag's receive times instead, with a note;
//   * the nominal step is the median step between consecutive messages;
//   * each message is given a slot on the grid: the number of steps, rounded, from the first
//     stamp, less the grid's phase. The step and the phase are found from the stamps' phases
//     on the grid (circular means: a dropped message shifts the later stamps by a whole step,
//     which leaves their phase alone), the phase over a window of about 4000 messages, so
//     that a slow drift of the host's clock against the sensor's is followed. Rounding
//     against the grid rather than against the previous stamp is what keeps jitter from
//     making gaps: two stamps within +-40 % of their places can be 0.2 or 1.8 steps apart,
//     and are still on neighbouring slots. Jitter of +-30 % and +-40 % is tested;
//   * a message whose slot is that of the previous message, or that comes earlier (a repeated
//     or out-of-order stamp), is dropped and counted (StampTiming::duplicates_dropped, a note);
//   * slots skipped are a gap of that many missing samples (core/gaps.h): a dropped message
//     is a gap of one sample. Nothing is interpolated;
//   * the sample rate is refined by a least-squares fit of stamp against slot over the whole
//     record, and the jitter is the fit's residual (rms and largest magnitude).
// BagReadOptions::sample_rate_hz skips all this (as ReadOptions::sample_rate_hz does for the
// other formats): every message is a sample, in bag order, at the given rate, without gaps.
//
// Messages are read in the bag's order (by receive time), which is the order of the stamps in
// any normal recording; a stamp out of order is handled as above.
//
// Errors (core/error.h): an option that cannot be used (an unknown topic, a topic of another
// type, several IMU topics and none chosen) is a UsageError (exit 2) listing the candidates;
// content that cannot be used (not a bag, truncated, corrupt, no sensor_msgs/Imu topic, fewer
// than two messages, a NaN or infinite value) is a DataError (exit 3) whose message starts
// with the quoted file name and names the topic, the 1-based message index and the field.
//
// Size and speed: a sensor_msgs/Imu message takes 373 bytes of bag (315 of message with a
// 3-character frame_id, its record header and index entry), so an 8 h record at 400 Hz
// (1.15e7 messages) is a bag of 4.3 GB. The library loads the bag's whole index when it opens
// it (a tree node of 64 bytes a message) and parses each message's record header into a map.
// The bag is opened and read in a child process (rosbag crashes on some damaged bags; the
// crash is then a DataError), which sends the messages through a pipe, block by block, while
// this process stores them: the 8 h bag is read in about 6 s on 2 cores (bench/RESULTS.md),
// and the result takes 48 bytes a sample in this process.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "foglab/core/gaps.h"
#include "foglab/core/language.h"

namespace foglab::io {

/// The ROS message type read_imu_bag() reads.
inline constexpr const char* kImuMessageType = "sensor_msgs/Imu";

/// One topic of a bag.
struct BagTopic {
  std::string name;            ///< e.g. "/imu/data"
  std::string type;            ///< message type, e.g. "sensor_msgs/Imu"
  std::uint64_t messages = 0;  ///< messages on the topic
};

/// Whether `path` ends in `.bag` (any case): what the readers take for a ROS 1 bag.
bool has_bag_extension(const std::string& path);

/// Every topic of a bag with its message type and count, sorted by name (for listings and
/// messages). Throws DataError when `path` is not a readable ROS 1 bag, UsageError when it
/// cannot be opened.
std::vector<BagTopic> list_bag_topics(const std::string& path);

/// How to read an IMU topic from a bag.
struct BagReadOptions {
  /// The topic to read. Empty: the only sensor_msgs/Imu topic of the bag (with several, a
  /// UsageError listing them).
  std::string topic;
  /// [Hz] Sample rate; when set (> 0), the stamps are not used: every message is a sample, in
  /// bag order, no gaps, no duplicates dropped, no jitter figures.
  std::optional<double> sample_rate_hz;
  /// The most messages read from the topic; more is a DataError naming the limit (checked
  /// from the index, before anything is read). No limit by default; the CLI sets one from the
  /// memory available.
  std::optional<std::size_t> max_samples;
};

/// What the stamps say about the time axis.
struct StampTiming {
  std::uint64_t messages = 0;            ///< messages read from the topic
  double median_step_s = 0.0;            ///< [s] median step between consecutive stamps
  double jitter_rms_s = 0.0;             ///< [s] rms of stamp minus its place on the fitted grid
  double jitter_max_s = 0.0;             ///< [s] largest magnitude of that difference
  std::uint64_t duplicates_dropped = 0;  ///< messages on the previous one's slot, or earlier
  /// "header.stamp", or "bag receive time" when every header stamp is zero.
  std::string stamp_source;
};

/// An IMU record read from a bag: the samples present, their gaps, and how the time was found.
struct ImuRecord {
  std::string path;      ///< as given
  std::string topic;     ///< the topic read
  std::string frame_id;  ///< header.frame_id of the first message
  /// [Hz] From the stamps (1 / slope of the fit of stamp against slot), or
  /// BagReadOptions::sample_rate_hz.
  double sample_rate_hz = 0.0;
  double start_time_s = 0.0;  ///< [s] the first message's stamp (ROS time: since 1970)
  /// Stretches of missing samples (dropped messages); empty with BagReadOptions::sample_rate_hz.
  std::vector<Gap> gaps;
  StampTiming timing;
  /// [rad/s] angular_velocity x, y, z of the samples present, as in the bag.
  std::array<std::vector<double>, 3> angular_velocity_rad_s;
  /// [m/s^2] linear_acceleration x, y, z, as in the bag.
  std::array<std::vector<double>, 3> linear_acceleration_m_s2;
  /// What a user should know about how the samples were read (duplicates dropped, receive
  /// times used, gaps); the CLI prints each as a note.
  std::vector<Message> notes;
};

/// Reads a topic of sensor_msgs/Imu messages (see the top of this header). Needs at least two
/// messages; the values must be finite. Throws UsageError / DataError as described above.
ImuRecord read_imu_bag(const std::string& path, const BagReadOptions& options = {});

/// The content of a bag write_imu_bag() writes: one topic of sensor_msgs/Imu messages.
struct ImuBagContent {
  std::string topic = "/imu";
  std::string frame_id = "imu";
  /// [s] header.stamp of each message (ROS time: 0 to 4294967295 s, stored to the nanosecond
  /// nearest the double, which holds a time of 1.7e9 s, a date of 2023, to 0.24 us); any
  /// spacing and order (tests add jitter, drops and duplicates).
  std::vector<double> stamps_s;
  /// [s] The bag's receive time of each message, the order in which it is stored. Empty: the
  /// stamps (a zero stamp is received at 1 ns, the earliest time a bag can hold).
  std::vector<double> receive_times_s;
  std::array<std::vector<double>, 3> angular_velocity_rad_s;    ///< [rad/s] one per stamp
  std::array<std::vector<double>, 3> linear_acceleration_m_s2;  ///< [m/s^2] one per stamp
};

/// Writes `content` as a ROS 1 bag (uncompressed chunks). The bag is written to a temporary
/// beside `path` and renamed into place when complete (core/output.h), so there is never a
/// half-written bag at `path`, and an interrupted run leaves none behind. Throws UsageError
/// for content that cannot be written (lengths that differ, a stamp outside ROS time, an
/// empty topic name) or an unwritable destination, DataError when the system cannot store the
/// file (a full disk).
void write_imu_bag(const std::string& path, const ImuBagContent& content);

}  // namespace foglab::io
