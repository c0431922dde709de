// foglab — does the short-tau Allan variance stay the same over a record?
//
// The Allan deviation's 95 % intervals (edf.h) assume a stationary record:
// the same process from the first sample to the last. A real sensor's
// short-term noise can change during a run: its white level rises a few
// per cent as it warms up, or a structural resonance moves with the
// temperature (the ADIS16405 imu1 z axis's resonance moves from about 22 Hz
// to 20 Hz over the first hour of its record, docs/validation.md). The
// whole-record Allan variance is then the average of a changing one, and its
// intervals understate how far it is from any one process.
//
// The check: the record is cut into `blocks` equal pieces of its samples in
// time order, the overlapping Allan variance at m samples is computed
// inside each by allan_deviation() (the block's gaps pooled as it pools
// them), and the Mann–Kendall test (Mann 1945; Kendall 1975: S, the sum of
// sign(v_j - v_i) over the pairs i < j, against its variance
// n (n - 1) (2 n + 5) / 18 under independent, identically distributed v)
// asks whether the blocks' values trend in time. The test counts orders
// only, so it needs no model of the values' spread (a resonance's Allan
// variance scatters more than a power-law noise's edf says) and a spike or
// a step in one block moves one rank. The blocks' values are independent
// where the Allan variance's terms are correlated over far fewer samples
// than a block holds: only taus whose m-sample clusters fit at least
// `min_clusters` times in a block are checked (short taus, where the white
// noise, the output filter and lines rule; flicker and random walk add
// there the same amount in every block).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "foglab/core/gaps.h"

namespace foglab::stats {

struct AllanDriftOptions {
  int blocks = 32;                  ///< pieces of the record, in time order
  std::int64_t min_clusters = 256;  ///< a block holds at least this many m-sample clusters
  /// |z| at or beyond which a tau is called drifting: two-sided p < 1e-4
  /// per tau, so that the handful of taus checked on a stationary record
  /// raise no call in about a thousand records.
  double z_threshold = 3.8906;
};

/// The taus a check calls, and the ranges of their |z| and last/first ratio.
struct AllanDriftCalls {
  std::vector<double> tau_s;                 ///< [s] the taus called (empty: none)
  double z_low = 0.0, z_high = 0.0;          ///< |trend_z| over them
  double ratio_low = 0.0, ratio_high = 0.0;  ///< last_to_first over them
  double largest_z = 0.0;                    ///< |trend_z| over every tau checked
};

struct AllanDrift {
  int blocks = 0;               ///< 0: the record is too short for the check
  std::vector<double> tau_s;    ///< [s] the taus checked (octaves from tau0)
  std::vector<double> trend_z;  ///< Mann–Kendall z (continuity-corrected), + rising
  /// The last eighth of the blocks' mean Allan variance over the first
  /// eighth's (dimensionless).
  std::vector<double> last_to_first;
  std::vector<bool> drifting;  ///< |trend_z| >= the threshold
  /// The blocks each tau's test used: a block whose gaps leave it fewer
  /// than a quarter of its terms is left out (at least 16 remain, or the
  /// tau is not checked).
  std::vector<int> blocks_used;
  /// [s] each block's middle, from the record's first sample (the gaps'
  /// missing samples counted), for a plot of the values over the run.
  std::vector<double> block_time_s;
  /// block_adev[i][b]: the Allan deviation at tau_s[i] inside block b (the
  /// rate's unit; NaN where the block is left out of that tau's test).
  std::vector<std::vector<double>> block_adev;
  double z_threshold = 0.0;
  bool any() const;
  AllanDriftCalls calls() const;
};

/// The check on `rate` (any unit; sampled every `tau0_s`) with its `gaps`
/// (core/gaps.h, as allan_deviation() takes them).
AllanDrift allan_drift(std::span<const double> rate, double tau0_s, std::span<const Gap> gaps = {},
                       const AllanDriftOptions& options = {});

}  // namespace foglab::stats
