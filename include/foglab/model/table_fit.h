// foglab — the noise model fitted to an Allan deviation table alone.
//
// When all a user has is the table (Stable32's output, a vendor's test
// report, `foglab allan --csv`), the model is fitted to its points as
// fit_noise_model()'s span form does for a record's own: gamma-deviance
// weights from each point's equivalent degrees of freedom, the averaging
// factors unknown (correlation_inflation). The edf comes from the best the
// table holds:
//   1. an edf column;
//   2. the 68 % bounds: the edf whose chi-square interval has their width
//      (stats::edf_from_interval);
//   3. the counts n, taken as OADEV terms (N = n + 2m phase points, m from
//      the table's m column, else tau / tau_1 with the first tau at m = 1):
//      SP 1065's white-FM OADEV edf, [3(N-1)/(2m) - 2(N-2)/N] 4m^2/(4m^2+5);
//   4. nothing: the fit needs weights, so it assumes a record of 10 times
//      the longest tau (the lab's ten clusters there) with the counts of 3.,
//      and the result says what such a table cannot support: no intervals
//      and no upper bounds, and terms resolved on assumed weights.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "foglab/core/accuracy_class.h"
#include "foglab/model/noise_fit.h"

namespace foglab::model {

/// Where a table's edf came from (see above).
enum class TableEdfSource { edf_column, bounds, counts, assumed };
/// "edf_column", "bounds", "counts", "assumed".
std::string_view to_string(TableEdfSource source);

/// A table's columns; the optional ones empty when the table lacks them
/// (ci68_low/high, edf NaN at single rows without them).
struct TableColumns {
  std::span<const double> tau_s;  ///< [s] increasing
  std::span<const double> dev;    ///< [deg/h]
  std::span<const std::int64_t> n, m;
  std::span<const double> edf, ci68_low, ci68_high;
};

struct TableFit {
  NoiseFitResult fit;
  std::vector<double> edf;  ///< the edf used at each tau
  TableEdfSource edf_source = TableEdfSource::assumed;
  double bias_instability_deg_h = 0.0;  ///< the table's minimum deviation
  double bias_instability_tau_s = 0.0;
  double arw_deg_sqrt_h = 0.0;  ///< from the fitted N (NaN if none)
  ClassVerdict verdict;
  std::vector<Message> notes;  ///< what the table could not support, and why
};

/// Fits the model to `table`. Throws UsageError for mismatched column
/// sizes or fewer than 3 points.
TableFit fit_allan_table(const TableColumns& table, const NoiseFitOptions& options = {});

}  // namespace foglab::model
