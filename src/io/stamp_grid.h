// foglab — placing time stamps that jitter on the uniform grid of the samples they stamp
// (internal to the readers: the ROS bag reader, and the text and MAT readers when a time
// column is not evenly spaced).
//
// A sensor samples on its own clock; the times a logger writes beside the samples (a
// driver's header.stamp, a host's clock when the sample arrived) scatter about that
// sampling grid. The grid is found from the stamps' phases on it (circular statistics; the
// method is in stamp_grid.cc), each stamp is given the nearest slot of the grid, a slot
// skipped is a gap of that many missing samples (core/gaps.h: nothing is interpolated), and a
// stamp on the slot of the stamp before it, or earlier, is dropped. Jitter of up to +-40 % of
// a step is placed without a false gap (tests/io/stamp_grid_test.cc).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "foglab/core/gaps.h"

namespace foglab::io::internal {

/// Where the stamps of a record sit on their grid.
struct StampGrid {
  /// [s] the grid's step: the least-squares slope of stamp against slot over the samples kept
  double step_s = 0.0;
  double jitter_rms_s = 0.0;  ///< [s] rms of stamp minus the fitted line of stamp against slot
  double jitter_max_s = 0.0;  ///< [s] largest magnitude of that difference
  /// rms distance of the stamps from their slots on the grid that follows the phase along the
  /// record [steps]: 0.29 when the stamps are spread evenly over the step (no grid at all),
  /// 0.23 for jitter uniform over +-40 % of a step
  double scatter_rms_steps = 0.0;
  /// Gaps between the samples kept; Gap::before_sample counts kept samples.
  std::vector<Gap> gaps;
  /// Indexes of the stamps dropped (on the slot of the stamp before them, or earlier), in
  /// increasing order.
  std::vector<std::size_t> dropped;
};

/// The most StampGrid::scatter_rms_steps of stamps read as a grid with jitter: beyond it they
/// are taken to have no grid (evenly spread phases give 0.29), and the readers refuse them.
inline constexpr double kMostScatterSteps = 0.25;

/// The median of the positive steps between consecutive stamps [s]; 0 when no step is
/// positive.
double median_step_s(std::span<const std::int64_t> stamps_ns);

/// Places `stamps_ns` (in the order of the samples) on their grid, from `median_s`
/// (median_step_s(stamps_ns), which the caller has already). step_s is 0 when there are fewer
/// than two stamps, the median step is not positive or the samples kept give no positive
/// slope.
StampGrid fit_stamp_grid(std::span<const std::int64_t> stamps_ns, double median_s);

/// `values` without the entries at `dropped` (increasing indexes), in place.
void drop_entries(std::vector<double>& values, const std::vector<std::size_t>& dropped);

}  // namespace foglab::io::internal
