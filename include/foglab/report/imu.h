// foglab — the report of a whole IMU: several axes of gyroscopes and
// accelerometers analysed together (`foglab analyze --channels ...`, a ROS
// bag). Each axis has its own analysis (model/analysis.h) and its own
// report (report.h); this adds what is read across the axes:
//
//   * a Markdown summary with a row per axis, and a table for filter
//     designers: each axis's white noise and bias random walk,
//     continuous-time and per sample;
//   * Kalibr's imu.yaml for both sensors;
//   * for the HTML page, one Allan plot per sensor with all its axes
//     overlaid (each with its fitted model), before the axes' own sections.
//
// Kalibr's IMU noise model (https://github.com/ethz-asl/kalibr/wiki/IMU-Noise-Model)
// takes continuous-time values, one per sensor:
//   gyroscope_noise_density      [rad/s/sqrt(Hz)]   = N [deg/h/sqrt(Hz)] * (pi/180)/3600
//   gyroscope_random_walk        [rad/s^2/sqrt(Hz)] = K [deg/h/sqrt(s)]  * (pi/180)/3600
//   accelerometer_noise_density  [m/s^2/sqrt(Hz)]   = N [m/s^2/sqrt(Hz)]
//   accelerometer_random_walk    [m/s^3/sqrt(Hz)]   = K [m/s^2/sqrt(s)]
// and a filter running at the sample interval dt uses the discrete values
//   sigma_d = sigma / sqrt(dt)   (white noise, per sample)
//   sigma_bd = sigma_b * sqrt(dt) (bias random walk, per sample)
// (the same wiki page). One value per sensor: the root mean square of its
// axes' values (the mean of their noise powers), each axis listed in a
// comment. When an axis's fit does not resolve the random walk, its 95 %
// upper bound stands in for it, and the comment says so.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "foglab/core/units.h"
#include "foglab/model/analysis.h"
#include "foglab/report/plot.h"
#include "foglab/report/report.h"

namespace foglab::report {

/// One axis of an IMU and its analysis (in the sensor's internal unit:
/// deg/h or m/s^2).
struct ImuAxis {
  std::string channel;  ///< e.g. "gyro_x"
  Sensor sensor = Sensor::gyroscope;
  const model::AnalysisResult* result = nullptr;
};

/// What a navigation filter (and Kalibr) takes from one axis, in the
/// analysis's units: the white-noise density N (deg/h/sqrt(Hz) or
/// m/s^2/sqrt(Hz)) and the bias random walk K (deg/h/sqrt(s) or
/// m/s^2/sqrt(s)), continuous-time, each with a sentence saying where it
/// came from: the fit's resolved value with its 95 % interval, else a
/// graphical reading or a 95 % upper bound. An unresolved K's bound is the
/// fit's, or, when tighter, the one the Allan deviation sets directly: the
/// smallest ci95_high(tau) / sqrt(tau / 3) over the taus (a random walk
/// alone, K sqrt(tau/3), cannot stand above the record's upper limit).
struct FilterNoise {
  double white = 0.0;
  double white_low = 0.0, white_high = 0.0;  ///< 95 % interval (NaN when not resolved)
  bool white_resolved = false;
  std::string white_source;
  double random_walk = 0.0;
  double random_walk_low = 0.0, random_walk_high = 0.0;  ///< 95 % (NaN when not resolved)
  bool random_walk_resolved = false;
  std::string random_walk_source;
};
FilterNoise filter_noise(const model::AnalysisResult& result, Sensor sensor);

/// The per-axis values converted to Kalibr's units (rad/s... for a
/// gyroscope, m/s^2... for an accelerometer): the factor by which N and K
/// are multiplied.
double kalibr_factor(Sensor sensor);

/// Kalibr's four values, in its units, as imu.yaml writes them (NaN for a
/// sensor without axes).
struct KalibrValues {
  double gyroscope_noise_density = 0.0;      ///< [rad/s/sqrt(Hz)]
  double gyroscope_random_walk = 0.0;        ///< [rad/s^2/sqrt(Hz)]
  double accelerometer_noise_density = 0.0;  ///< [m/s^2/sqrt(Hz)]
  double accelerometer_random_walk = 0.0;    ///< [m/s^3/sqrt(Hz)]
};
KalibrValues kalibr_values(std::span<const ImuAxis> axes);

/// Kalibr's imu.yaml for every sensor among `axes` (a sensor without axes
/// is commented out), update_rate = `update_rate_hz`.
std::string kalibr_imu_yaml(std::span<const ImuAxis> axes, std::string_view file_name,
                            double update_rate_hz, std::string_view rostopic = "/imu0");

/// The Markdown summary of an IMU: a row per axis, the filter designers'
/// table, then each axis's notes.
std::string imu_markdown(std::span<const ImuAxis> axes, std::string_view title);

/// One plot per sensor among `axes` (gyroscopes first): the Allan deviation
/// of each of its axes overlaid, with each axis's fitted model dashed.
std::vector<Plot> imu_allan_plots(std::span<const ImuAxis> axes, std::string_view title);

/// The IMU's self-contained HTML page: the summary table, one overlaid
/// Allan plot per sensor, then every axis's own report section
/// (`axis_reports`, from make_report() of each axis in `axes`' order, made
/// with distinct ReportOptions::id_prefix values).
std::string imu_html(std::span<const ImuAxis> axes, std::span<const Report> axis_reports,
                     std::string_view title, const ReportOptions& options);

}  // namespace foglab::report
