// foglab — bias steps: jumps of the bias at an instant (a power glitch, a
// mode change, a knock that shifts the sensor), found and levelled before
// the statistics, with what was done stated.
//
// At window lengths W = 64, 128, ... samples (up to a 64th of the
// record) the difference D(k) between the means of the W samples after k
// and the W before is compared with its own robust spread (1.4826 times the
// median absolute deviation from the median of D over the record, which a
// few steps do not move, and which a steady drift does not enter: it moves
// the median). The largest |D - median| beyond `threshold` spreads, at any
// length, is a step; its sample is the best single change point of the
// stretch W either side (the largest |mean after - mean before| sqrt(l r /
// (l + r))), its size the difference of the means over up to 4 W either
// side of it (over W/8, doubled while the size stays within the noise of
// the last: a nearer change, the other edge of a short pulse, ends it),
// both with the record's drift (the median of D over W) taken out. It is
// levelled (its size subtracted from every later sample) and the search
// repeats. A bias that jumps as a process (a random telegraph or popcorn
// noise) is no set of steps: when more than `max_steps` are found,
// levelling two or more makes the record wander more (the mean square
// difference of neighbouring sixteenths of the record), or four or more go
// back and forth between two levels (three quarters of the neighbouring
// pairs opposite and within a quarter of their size), none is levelled
// (BiasSteps::left_as_noise). The windows stay inside the
// contiguous stretches between gaps (a jump across a gap is the process
// moving while nothing was recorded, not a step: it is measured on its
// own, GapJump), and the search runs on
// the record less a baseline when one is given (the temperature law, whose
// curvature would otherwise enter the spread of D or look like a step).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "foglab/core/gaps.h"

namespace foglab::model {

struct StepOptions {
  bool remove = true;      ///< level them (else only report them)
  double threshold = 6.0;  ///< robust spreads of D
  int max_steps = 20;
  /// > 0: for the search only, a sample departing from its neighbours'
  /// mean by more than this [deg/h] is pulled in to that distance (the
  /// record keeps it). The analysis sets it for heavy-tailed noise
  /// (spikes.h), whose single outliers, left in as the noise's own, would
  /// move a window mean as a step does.
  double outlier_clip_deg_h = 0.0;
};

/// A jump of the bias across a gap (a power glitch that lost samples and
/// shifted the bias, or the process moving while nothing was recorded). It
/// is measured, not levelled: the statistics use the stretches apart, so
/// it does not enter them. At window lengths W = 64, 128, ... (both
/// stretches holding W) the last W samples before the gap and the first W
/// after it are compared with the same difference taken as far apart
/// wherever nothing is missing: its median is the drift over that time,
/// its robust spread what the noise itself (random walk and flicker
/// included) moves the bias by across such a gap. The size is the
/// difference of the means over up to 4 W either side, the record's drift
/// over the time between them taken out.
struct GapJump {
  std::int64_t before_sample = 0;   ///< the gap's: the first sample after it
  double size_deg_h = 0.0;          ///< [deg/h]
  std::int64_t window_samples = 0;  ///< W: the most significant one; the longest if none is judged
  /// |D - median| / spread at W; NaN where no stretch holds two windows
  /// that far apart (a gap longer than the stretches: not judged)
  double significance = 0.0;
  bool significant = false;  ///< beyond StepOptions::threshold
};

struct BiasSteps {
  std::vector<std::int64_t> indices;         ///< the first sample after each step, in time order
  std::vector<double> sizes_deg_h;           ///< [deg/h]
  std::vector<std::int64_t> window_samples;  ///< W at which each was found
  std::vector<double> significance;          ///< |D - median| / spread there
  bool removed = false;
  /// The bias jumps as a process (a random telegraph or popcorn noise),
  /// not at a few glitches: the jumps are listed (at most max_steps) and
  /// none is levelled. Why (none: they are steps).
  enum class AsNoise { none, beyond_limit, wander, two_levels };
  AsNoise left_as_noise_because = AsNoise::none;
  bool left_as_noise() const { return left_as_noise_because != AsNoise::none; }
  /// Set by analyze() (analysis.h): two or more jumps, each at a turn of the record's
  /// temperature (where its rate of change changes sign), all one way against the change of
  /// that rate: a bias that follows dT/dt (a FOG coil's Shupe effect), which the polynomial
  /// temperature law does not take out. Such jumps are levelled (with StepOptions::remove)
  /// even where they go back and forth between two levels.
  bool at_temperature_turns = false;
  /// Each gap whose stretches either side hold a window (64 samples or
  /// more, as for the steps), in time order.
  std::vector<GapJump> across_gaps;
};

/// Finds the bias steps of `rate_deg_h` and, with options.remove, levels
/// the record in place. A step smaller than `lsb_deg_h` (the output word's
/// step; 0: unknown) or of size 0 is none, and ends the search (on a
/// coarse output word one step of size 0 had been found again and again;
/// give it only where the output word distorts the noise: in a word finer
/// than the noise the mean moves by any amount). `gaps`: the record's gaps
/// (as for the statistics). `baseline_deg_h`: empty, or one value per
/// sample subtracted before the search (not from the record). Throws
/// UsageError for a baseline of another length or gaps outside the record.
BiasSteps find_steps(std::span<double> rate_deg_h, const StepOptions& options = {},
                     double lsb_deg_h = 0.0, std::span<const Gap> gaps = {},
                     std::span<const double> baseline_deg_h = {});

/// Levels `rate_deg_h` at `steps`: each step's size subtracted from every sample from its
/// index on (what find_steps() does with StepOptions::remove).
void level_steps(std::span<double> rate_deg_h, const BiasSteps& steps);

}  // namespace foglab::model
