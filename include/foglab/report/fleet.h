// foglab — the report of a fleet (`foglab batch`): a row per unit with its
// noise parameters and their 95 % intervals, the fleet's distribution of
// each parameter (model/fleet.h: median and spread on log10, the units
// that stand out), a class histogram, and the failures.
//
// Forms: CSV (a row per unit, units in the column names), Markdown (for the
// terminal and for reading on a forge), and a self-contained HTML page with
// a plot per parameter: the units' values ranked (an empirical quantile
// plot, log scale) with the fleet's median and the outlier limits
// median x 10^(+-z spread) drawn across, the outliers marked.
#pragma once

#include <string>
#include <vector>

#include "foglab/model/fleet.h"
#include "foglab/report/plot.h"
#include "foglab/report/report.h"
#include "foglab/stats/allan_drift.h"

namespace foglab::report {

/// A noise term of one unit as the analysis gave it (units: the term's).
struct FleetTerm {
  double value = 0.0;     ///< the estimate, or the 95 % upper bound of a term not resolved
  double ci95_low = 0.0;  ///< NaN when there is no interval
  double ci95_high = 0.0;
  std::string status;  ///< "resolved", "upper_bound", ... (model::TermStatus as text)
};

/// One unit (a gyroscope: a file, or a channel of a multi-axis file).
struct FleetRow {
  std::string unit;  ///< its name in the fleet
  std::string file;
  std::string channel;
  FleetTerm N;                          ///< [deg/h/sqrt(Hz)]
  FleetTerm B;                          ///< [deg/h]
  FleetTerm K;                          ///< [deg/h/sqrt(s)]
  double bias_instability_deg_h = 0.0;  ///< the ADEV minimum
  double bias_instability_tau_s = 0.0;
  /// The 95 % interval of the Allan deviation at that tau (NaN: none).
  double bias_instability_ci95_low = 0.0, bias_instability_ci95_high = 0.0;
  double arw_deg_sqrt_h = 0.0;
  std::string random_bias;     ///< "none", "wiener", "gauss_markov"
  std::string accuracy_class;  ///< Table 1's, empty when none
  /// The short taus' stationarity check (stats/allan_drift.h): the taus
  /// whose Allan deviation trends over the run, and whether it was made.
  stats::AllanDriftCalls short_tau_trend;
  bool short_tau_checked = false;
};

/// A record that could not be analysed.
struct FleetFailure {
  std::string input;  ///< the file (and channel)
  std::string message;
  int exit_code = 3;  ///< what `analyze` would have exited with (2 usage, 3 data)
};

/// The parameters a fleet is summarised on, in order, with their units:
/// N, B, K (each only where the analysis resolved it) and the bias
/// instability (the ADEV minimum, always read).
struct FleetParameter {
  const char* name;
  const char* unit;
};
inline constexpr FleetParameter kFleetParameters[] = {
    {"N", "deg/h/sqrt(Hz)"}, {"B", "deg/h"}, {"K", "deg/h/sqrt(s)"}, {"bias_instability", "deg/h"}};

/// The rows as model::fleet units (a term counts only where resolved), with
/// their 95 % intervals.
std::vector<model::FleetUnit> fleet_units(const std::vector<FleetRow>& rows);

struct FleetReport {
  std::string title;
  std::vector<FleetRow> rows;
  model::FleetSummary summary;  ///< of fleet_units(rows) on kFleetParameters
  double outlier_z = 3.5;       ///< the limit the summary used
  std::vector<FleetFailure> failures;
  std::size_t reused = 0;  ///< units whose earlier result was kept (a rerun)
};

/// A row per unit, with the parameters it stands out on.
std::string fleet_csv(const FleetReport& fleet);
/// The fleet in Markdown: counts, the distribution table, the outliers, the
/// class histogram, the failures, and the units' table.
std::string fleet_markdown(const FleetReport& fleet);
/// A ranked-values plot per parameter with at least two units.
std::vector<Plot> fleet_plots(const FleetReport& fleet);
/// The whole fleet as a self-contained HTML page (plots by gnuplot, or a
/// note saying why they are missing).
std::string fleet_html(const FleetReport& fleet, const ReportOptions& options = {});

}  // namespace foglab::report
