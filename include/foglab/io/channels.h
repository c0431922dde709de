// foglab — which channel of a record is which: the naming rules shared by
// the readers and every program that pairs channels.
//
//   * Time: a variable or column named `t`, `time` or `time_s` (text
//     headers without regard to case, except that a column named exactly
//     `T` is the lab's temperature, never time) gives the sample rate.
//   * Rate: the lab's files hold `Y1` and `Y2` (the lab manual's lab 2:
//     `f, t, Y1, Y2, T1, T2`); generate's CSV holds `rate`. With several
//     data channels and none chosen, `Y1` is read (text: `Y1` or `rate`,
//     without regard to case).
//   * Temperature: the lab's `T`, `T1`, `T2`, ... are never data channels.
//     A rate channel pairs with a temperature by name: a name ending in
//     digits d with `T` + d (`Y1` with `T1`, `Y2` with `T2`), a name without
//     digits (`rate`) with `T` or `temperature`.
//   * Inertial sensors: a name says gyroscope when, ignoring case, it
//     holds `gyr`, `omega` or `angular`, or is `g`, `w` or `wx`-like (`gx`,
//     `w_y`, `gyro_z_dps`); it says accelerometer when it holds `acc` or
//     `linear`, or is `a` + an axis (`ax`, `a_z`, `accel_x_mg`). A ROS bag's
//     channels are `gyro_x`, `gyro_y`, `gyro_z`, `accel_x`, `accel_y`,
//     `accel_z`.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "foglab/core/units.h"

namespace foglab::io {

/// The automatic time-channel names, in order of preference.
inline constexpr std::array<std::string_view, 3> kTimeChannelNames = {"t", "time", "time_s"};

/// The data channels read when a file has several and none was chosen, in
/// order of preference (MAT: the first only; text: both, without regard
/// to case).
inline constexpr std::array<std::string_view, 2> kDefaultDataChannels = {"Y1", "rate"};

/// How a channel name is compared: exactly (MAT variables) or without regard
/// to case (text headers).
enum class NameMatch { exact, ignore_case };

/// True for a name of kTimeChannelNames; ignoring case (text headers) also
/// `Time`, `TIME_S`, ..., but never `T`.
bool is_time_channel_name(std::string_view name, NameMatch match);

/// True for the lab's temperature names `T`, `T1`, `T2`, ....
bool is_lab_temperature_name(std::string_view name);

/// The temperature channel names that pair with a rate channel, in order
/// of preference: `T1` for `Y1`, `T` and `temperature` for `rate`, none for
/// a bare column index such as `2`.
std::vector<std::string> paired_temperature_names(std::string_view rate_channel);

/// The channel of `channels` called `name`: exactly, else (ignoring case)
/// without regard to case, but never a time channel standing in for the
/// lab's temperature `T`.
std::optional<std::string> find_channel(const std::vector<std::string>& channels,
                                        std::string_view name, NameMatch match);

/// An IMU's six channels, gyroscopes then accelerometers: a ROS bag's
/// (io/rosbag.h), and the columns `generate --imu` writes.
inline constexpr std::array<std::string_view, 6> kImuChannels = {"gyro_x",  "gyro_y",  "gyro_z",
                                                                 "accel_x", "accel_y", "accel_z"};

/// The sensor a channel's name says it belongs to (the rules above), or
/// none (`Y1`, `rate`, `2`, `temperature`).
std::optional<Sensor> sensor_by_name(std::string_view name);

/// The channels of `channels` whose names say gyroscope or accelerometer,
/// in their order.
std::vector<std::string> inertial_channels(const std::vector<std::string>& channels);

/// Channel names for a message: "a, b, c"; with more than kListedNames,
/// the first ones, "...", the last one and the count ("(1200 in all)"),
/// each name cut to 40 characters — a file with a million columns or a
/// megabyte name gives a message of one line.
std::string list_names(const std::vector<std::string>& names);
inline constexpr std::size_t kListedNames = 8;

}  // namespace foglab::io
