// foglab — reading an Allan deviation table someone else computed.
//
// Users often have only the table: Stable32's output, a vendor's test
// report, another tool's CSV, foglab's own `allan --csv`. read_allan_table()
// takes any of:
//   * a header line naming the columns (comma, semicolon, tab or space
//     separated; '#' lines are comments): tau (tau, tau_s, tau [s], t),
//     deviation (dev..., adev, oadev, totdev, sigma, allan..., deviation),
//     and optionally the count (n, #, count, terms), the averaging factor
//     (m, af), alpha, edf, the 68 % bounds (ci68_low/ci68_high, min
//     sigma/max sigma, low/high). foglab's `allan --csv` header is one;
//   * Stable32's printed table without a header: rows of seven numbers,
//     AF, tau, count, alpha, min sigma, sigma, max sigma ('#' header lines
//     as Stable32 writes them are skipped); bounds of 0 mean none.
// Values are in the table's own unit (foglab fits them as deg/h). A table
// of another statistic (MDEV, TDEV, the Hadamard or other total deviations,
// by its column name or Stable32's "Sigma Type") is refused: the model's
// Allan variance does not describe it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace foglab::io {

struct AllanTable {
  std::vector<double> tau_s;                ///< [s] increasing
  std::vector<double> dev;                  ///< deviation at each tau (> 0)
  std::vector<std::int64_t> n;              ///< number of terms; empty if not given
  std::vector<std::int64_t> m;              ///< averaging factors; empty if not given
  std::vector<int> alpha;                   ///< noise exponents; empty if not given
  std::vector<double> edf;                  ///< empty if not given
  std::vector<double> ci68_low, ci68_high;  ///< empty if not given (NaN where missing)
  std::string layout;                       ///< "header" or "stable32": how the columns were found
};

/// Reads `path`. Throws DataError naming the file and the line for a row
/// that is not numbers, a missing tau or deviation column, a non-positive or
/// non-increasing tau, a non-positive deviation, or fewer than 3 rows.
AllanTable read_allan_table(const std::string& path);

}  // namespace foglab::io
