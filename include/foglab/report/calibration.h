// foglab — the report of a rate-table calibration (model/calibration.h, `foglab calibrate
// --report`): the fitted eq. (10) with its intervals, the nonlinearity both ways, the noise
// and the weighting, the error budget of eq. (13), the corrected-rate equation (eq. 11),
// the plateaus, and the plots a test engineer looks at (gnuplot SVG, report/plot.h):
//   1. output against rate: the plateau means at each temperature and the fitted curve;
//   2. the plateaus' scale factors (u - u_rest) / w against rate, with the fitted
//      S(T) [1 + f(w)] at each temperature: the nonlinearity made visible;
//   3. the plateau residuals against rate;
//   4. the plateau residuals against temperature.
// A triad's report holds one section per gyro after the misalignment matrix. The text is
// ReportOptions::language's catalogue (core/language.h).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "foglab/model/calibration.h"
#include "foglab/core/language.h"
#include "foglab/report/report.h"

namespace foglab::report {

struct CalibrationReport {
  std::vector<Figure> figures;  ///< every gyro's, in order
  std::string html;             ///< the whole self-contained page
  std::string markdown;         ///< the same numbers and tables (report.md)
  bool plots_skipped = false;
  std::string plots_note;
};

/// The report of one gyro's calibration titled `title` (the run's name).
CalibrationReport make_calibration_report(const model::Calibration& calibration,
                                          std::string_view title,
                                          const ReportOptions& options = {});

/// A triad's: the misalignment matrix, then each gyro's section; `titles` name the three
/// mountings' files (x, y, z).
CalibrationReport make_triad_report(const model::TriadCalibration& triad, std::string_view title,
                                    const std::vector<std::string>& titles,
                                    const ReportOptions& options = {});

/// "v [lo, hi]" with the digits the interval's width asks for (at least 4), every number
/// times `scale` (1e6 for ppm).
std::string interval_text(const model::CalibratedValue& value, double scale = 1.0);

/// Eq. (11) with the fitted coefficients, as one line of text.
std::string corrected_rate_equation(const model::Calibration& calibration,
                                    Language language = Language::en);

/// The plot descriptions alone (no gnuplot run), in the figures' order.
std::vector<Plot> calibration_plots(const model::Calibration& calibration,
                                    Language language = Language::en);

}  // namespace foglab::report
