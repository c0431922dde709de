// foglab — the report of lab 1 (the manual's "Содержание отчета":
// the coil's numbers, the output against rate for each modulation and
// scheme, the sweep tables with scale factors and nonlinearity, and the
// analysis), from sim::run_lab1().
//
// Plots (gnuplot SVG, report/plot.h), units on every axis:
//   1. intensity at the detector against the total phase phi_s + dphi_m
//      ("I vs fi") for no, square and sine modulation, on the curve
//      gamma (1 + cos phi);
//   2. demodulated output against rate ("S vs Om") for each modulation, the
//      time simulation over the ramp with the analytic steady state;
//   3. time traces at a constant rate, one per modulation: detector and the
//      modulator's phase difference over a few modulation periods;
//   4. the open loop over the ramp against time: rate and output;
//   5. the sweeps: scale factor against rate, open loop (time, analytic,
//      sine) and closed loop (right-hand axis);
//   6. the closed loop under a ramp to 3 Omega_pi/2 beside the open loop
//      under the same ramp (output against input rate);
//   7. square modulation at a fraction of the proper frequency: the
//      transition spikes.
// The text is ReportOptions::language's catalogue (core/language.h): in
// Russian the manual's terms (фаза Саньяка, сигнал демодуляции, открытая
// схема и схема с обратной связью, масштабный коэффициент, нелинейность).
#pragma once

#include <string>
#include <vector>

#include "foglab/core/language.h"
#include "foglab/report/report.h"
#include "foglab/sim/lab1.h"

namespace foglab::report {

struct Lab1Report {
  std::vector<Figure> figures;
  std::string html;       ///< the whole self-contained page
  std::string markdown;   ///< numbers, tables and conclusions (for the terminal and report.md)
  std::string sweep_csv;  ///< the three sweeps, one line per rate
  bool plots_skipped = false;
  std::string plots_note;
};

/// Draws the plots and writes the page titled `title`; `loop` is the
/// closed-loop options the result was made with (for the ramp-lag theory).
/// The text, the figures' captions and the plots' titles, axes and legends
/// are in options.language (core/language.h); sweep_csv stays English, the
/// CLI's and the JSON's names.
Lab1Report make_lab1_report(const sim::Lab1Result& result, std::string_view title,
                            const sim::ClosedLoopOptions& loop = {},
                            const ReportOptions& options = {});

/// The plot descriptions alone (no gnuplot run), in the figures' order, their
/// text in `language`.
std::vector<Plot> lab1_plots(const sim::Lab1Result& result, Language language = Language::en);

}  // namespace foglab::report
