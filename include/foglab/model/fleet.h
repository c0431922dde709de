// foglab — a fleet of units (gyros of one type from a production batch, a test lab's
// stock): each unit's noise parameters side by side, the fleet's distribution of each, and
// the units that stand out of it.
//
// Noise parameters are positive scale factors whose spread across units is multiplicative
// (a unit twice as noisy as another is as far above the fleet as one half as noisy is
// below), so every statistic of the spread is taken on log10 of the values:
//   * the centre is the median (of an even count, the upper middle); the spread the median
//     absolute deviation (MAD) of log10, scaled by 1.4826 to estimate a normal sigma
//     (core/numeric.h's robust_spread(); robust: the outliers looked for do not widen it, as
//     they would a standard deviation);
//   * a unit stands out on a parameter when its modified z-score
//         M = 0.6745 (log10 x - median) / MAD = (log10 x - median) / (1.4826 MAD)
//     exceeds `FleetOptions::outlier_z` in magnitude (3.5, B. Iglewicz and D. C. Hoaglin,
//     "How to Detect and Handle Outliers", ASQC 1993: the rule's false-alarm rate for a
//     normal population is about 5e-4 a unit). With a MAD of zero (half the units or more
//     equal) no unit is flagged.
//   * a value is an estimate: a unit with a 95 % interval for the parameter stands out
//     only when the whole interval lies beyond the limit median x 10^(+-z spread). A unit
//     of a normal fleet whose estimate strays past the limit by its own error (a flicker
//     coefficient from an hour of data is uncertain by tens of per cent) is not flagged;
//     one whose parameter is, at 95 % confidence, beyond the fleet's is. The spread is
//     that of the estimates: the fleet's own spread widened by the units' estimation
//     errors (in quadrature, for independent errors).
// A value that is not finite or not positive (a term the analysis did not resolve) counts
// in no statistic and is never an outlier; the parameter's `units` says how many counted.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace foglab::model {

/// One unit's values, by parameter name (e.g. "N", "bias_instability", "K").
struct FleetUnit {
  std::string name;
  std::map<std::string, double> values;
  /// 95 % intervals (low, high) by parameter name, where the values are estimates that
  /// have them (a NaN end: open on that side).
  std::map<std::string, std::pair<double, double>> ci95;
  std::string accuracy_class;  ///< Table 1 class; empty when none
};

struct FleetOptions {
  double outlier_z = 3.5;  ///< modified z-score beyond which a unit stands out (> 0)
};

/// The fleet's distribution of one parameter (NaN where fewer than 2 units count).
struct ParameterSpread {
  std::string name;
  std::size_t units = 0;       ///< units with a finite, positive value
  double median = 0.0;         ///< in the parameter's unit
  double spread_log10 = 0.0;   ///< 1.4826 MAD of log10 values (a normal sigma of log10)
  double spread_factor = 0.0;  ///< 10^spread_log10: the typical factor between units
  double minimum = 0.0, maximum = 0.0;
  double p05 = 0.0, p95 = 0.0;  ///< 5th and 95th percentiles (linear interpolation)
};

/// A unit that stands out on a parameter.
struct FleetOutlier {
  std::string unit;
  std::string parameter;
  double value = 0.0;
  double modified_z = 0.0;    ///< signed: > 0 above the fleet
  double times_median = 0.0;  ///< value / the fleet's median
};

struct FleetSummary {
  std::size_t units = 0;
  std::vector<ParameterSpread> parameters;     ///< in the order of `parameters` asked for
  std::vector<FleetOutlier> outliers;          ///< by unit order, then parameter order
  std::map<std::string, std::size_t> classes;  ///< units per accuracy class ("" not counted)
};

/// The fleet's statistics of `parameters` over `units`. Throws UsageError for a bad
/// option.
FleetSummary summarize_fleet(const std::vector<FleetUnit>& units,
                             const std::vector<std::string>& parameters,
                             const FleetOptions& options = {});

}  // namespace foglab::model
