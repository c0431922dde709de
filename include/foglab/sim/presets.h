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

}  // namespace foglab::sim
