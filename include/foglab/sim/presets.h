// foglab — error models of real gyros and of each accuracy class.
//
// Datasheet figures map to the model as follows (IEEE Std 952 conventions):
//   * angle random walk ARW [deg/sqrt(h)]  ->  N = 60 ARW [deg/h/sqrt(Hz)];
//     a noise density quoted in (deg/h)/sqrt(Hz) is N itself;
//   * "bias instability" is the minimum of the Allan deviation [deg/h]; for a
//     flicker floor alone that minimum is 0.664 B, so B = BI / 0.664
//     (sqrt(2 ln2 / pi) = 0.6643);
//   * "bias drift at fixed temperature (1 sigma)" of the lab manual's Table 3
//     is taken as the bias instability likewise.
// Rate random walk, Gauss-Markov terms and temperature coefficients are not
// on the datasheets; the presets choose plausible values and say so.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "foglab/sim/error_model.h"

namespace foglab::sim {

struct Preset {
  std::string name;         ///< e.g. "kvh-dsp-3000", "class-navigation"
  std::string description;  ///< source and what was assumed
  std::string accuracy_class;  ///< Table 1 class: strategic|navigation|intermediate|tactical|consumer
  ErrorModel model;
  double sample_rate_hz = 10.0;  ///< typical output rate [Hz]
};

/// Every built-in preset: KVH DSP-3000, DSP-1750, DSP-1760 (lab manual
/// Fig. 15), the FOGs of the manual's Table 3, and one archetype per
/// accuracy class of Table 1.
const std::vector<Preset>& presets();

/// The preset of that name; throws UsageError listing the names otherwise.
const Preset& find_preset(std::string_view name);

/// A 6-axis IMU: each axis its own error model. The gyroscopes' models are
/// in deg/h (as every ErrorModel); the accelerometers' in m/s^2 in place of
/// deg/h (N m/s^2/sqrt(Hz), B m/s^2, K m/s^2/sqrt(s), bias m/s^2): the
/// processes are the same, only the unit differs.
struct ImuModel {
  std::string name;
  std::string description;
  /// gyroscope x, y, z, then accelerometer x, y, z (the order of
  /// io::kImuChannels, whose names the CLI writes them under)
  std::array<ErrorModel, 6> axes;
  double sample_rate_hz = 400.0;
};

/// A MEMS IMU of the kind robotics and navigation engineers record in ROS
/// bags, at 400 Hz: gyroscopes with a noise density of 0.0066 deg/s/sqrt(Hz)
/// (N = 23.8 deg/h/sqrt(Hz)) and a bias instability of 14.5 deg/h,
/// accelerometers with 230 ug/sqrt(Hz) (2.26e-3 m/s^2/sqrt(Hz)) and 27 ug
/// (2.7e-4 m/s^2), after a consumer IMU datasheet (Bosch BMI088); bias
/// random walks (gyroscope 2 deg/h/sqrt(s), about 1e-5 rad/s^2/sqrt(Hz);
/// accelerometer 4e-5 m/s^2/sqrt(s)) are not on the datasheet and chosen so
/// that an hours-long record resolves them. The axes differ by up to 15 %
/// (as a real triad's do), and accel_z carries gravity (+9.80665 m/s^2, the
/// IMU lying flat, z up).
ImuModel mems_imu_model();

}  // namespace foglab::sim
