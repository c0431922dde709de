// foglab — the truth of a fleet: gyros of one type (a production batch, a
// test lab's stock) whose noise coefficients scatter about a nominal model,
// and a few planted outliers, so that the fleet statistics of `foglab
// batch` (model/fleet.h) are tested against known values.
//
// Each unit's nonzero noise coefficients (N, B, K, R, Q, gm_sigma) are the
// nominal ones times independent log-normal factors 10^(spread_log10 z),
// z standard normal: the fleet's median of each is the nominal value and
// the standard deviation of its log10 is spread_log10, the statistics
// model/fleet.h estimates. An outlier unit has one coefficient multiplied
// further by `outlier_factor`, taking turns over the nonzero ones of
// N, B, K. The Gauss-Markov correlation time, the systematic part and the
// output chain are the nominal ones. Every draw is a pure function of
// (seed, unit, coefficient): the same spec gives the same fleet.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "foglab/sim/error_model.h"

namespace foglab::sim {

struct FleetSpec {
  std::size_t units = 0;        ///< > 0
  double spread_log10 = 0.1;    ///< sigma of log10 of each coefficient (0.1: a factor 1.26)
  std::size_t outliers = 0;     ///< at most units / 10
  double outlier_factor = 5.0;  ///< > 0 and not 1; below 1 an outlier is better than the fleet
  std::uint64_t seed = 1;
};

/// One unit of a fleet and how it was made.
struct FleetMember {
  ErrorModel model;
  std::string outlier_parameter;  ///< "N", "B" or "K"; empty for a typical unit
};

/// The fleet of `spec` about `nominal`. Throws UsageError for a spec out of
/// range or a nominal model with no noise coefficient to scatter.
std::vector<FleetMember> draw_fleet(const ErrorModel& nominal, const FleetSpec& spec);

}  // namespace foglab::sim
