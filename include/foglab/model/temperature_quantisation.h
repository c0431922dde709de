// foglab — a quantised temperature channel: found from its readings, and
// the temperature between its steps reconstructed for the temperature law.
//
// A digital temperature sensor reads in steps (0.0625 degC for many, 0.14
// degC for the ADIS16405's). While the temperature moves by less than a
// step per sample, the reading is a staircase: it holds for many samples,
// then steps. The rate follows the true temperature, so a temperature law
// fitted against the staircase leaves c1 times the staircase's error (a
// sawtooth of +-q/2 with the steps' period) in the residual: on a
// tactical-grade record ramped by 10 degC in 2 h (c1 3 deg/h/degC), B came
// out 14-19 % high at q = 0.0625 degC, and at 0.25-0.5 degC the sawtooth
// was taken for a Gauss-Markov process or for 20 bias steps.
//
// Found when the reading changes on at most a quarter of the samples and
// its distinct values lie on a grid (the gaps between neighbouring values
// whole multiples of the smallest, as for the rate's output word,
// output_quantisation.h). Reconstructed from the instants where the reading
// changes: there the temperature crosses the boundary between the two
// readings (the reading is the rounding to the nearest step), so it is
// that boundary, half-way between the two samples (where the reading
// flickers back and forth between the same two values, the sensor's noise
// near their boundary, the one crossing is at the mean of those instants);
// between the crossings the temperature is taken as linear. Before the
// first and after the last the neighbouring slope is extended, kept within
// the reading's own step. A monotone ramp comes back exactly; at a turning
// point the temperature is at most q/2 off, as the reading is.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace foglab::model {

struct TemperatureQuantisation {
  bool detected = false;
  double lsb_c = 0.0;                ///< [degC] the reading's step q
  std::int64_t distinct_values = 0;  ///< distinct readings
  std::int64_t changes = 0;          ///< samples where the reading changes
  double mean_hold_s = 0.0;          ///< [s] samples per reading, on average, over fs
};

/// Looks at every sample of `temperature_c` sampled at `sample_rate_hz`.
TemperatureQuantisation find_temperature_quantisation(std::span<const double> temperature_c,
                                                      double sample_rate_hz);

/// The temperature between the steps of its readings (above), one value per
/// sample; `lsb_c` the step (find_temperature_quantisation()).
std::vector<double> reconstruct_quantised_temperature(std::span<const double> temperature_c,
                                                      double lsb_c);

}  // namespace foglab::model
