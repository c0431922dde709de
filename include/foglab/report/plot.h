// foglab — a small gnuplot driver: a plot described as data, drawn as SVG.
//
// A Plot holds a title, axis labels (with their units: "tau [s]"), log-axis
// flags and series (lines, points, lines with points, or a filled band
// between two curves), each with its legend title. render_svg() writes a
// gnuplot script — the data inline as datablocks (`$d0 << EOD`), so no
// temporary files are needed — runs `gnuplot` with the script on its
// standard input and returns the SVG it prints on its standard output
// (terminal `svg`, fixed size, `font ",11"`, not `dynamic`, no mouse
// script: the SVG is self-contained and can be inlined in an HTML page).
//
// Equal decades (docs/conventions.md section 5: log-log axes with equal decades): both ranges
// are widened to whole decades and the plot's aspect ratio set to
// (y decades)/(x decades) with `set size ratio`, so one decade has the same
// length on both axes and a slope of -1/2 looks like one. When that ratio
// would make the plot flatter than `min_decade_ratio` (or taller than
// `max_decade_ratio`), decades are added to the short axis (split between
// its two ends) rather than giving up the equal decades.
//
// Text is passed to gnuplot in single-quoted strings (where only the quote
// itself needs escaping) with the terminal's `noenhanced` mode, so titles are
// printed as written ("T_ref", "Hz^(1/2)" keep their underscores and
// carets); gnuplot escapes `&` and `<` for the SVG itself. Control characters
// in titles become spaces.
//
// Missing gnuplot is an outcome, not an exception: the result carries no SVG
// and an error string, and the caller (report.h) says the plots were
// skipped.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace foglab::report {

enum class SeriesStyle {
  lines,        ///< a polyline (a break where a value is not finite / not positive on a log axis)
  points,       ///< markers only
  linespoints,  ///< both
  band,         ///< the area between y_low and y_high (a confidence band)
};

struct Series {
  std::string title;  ///< legend entry; empty: no legend entry
  SeriesStyle style = SeriesStyle::lines;
  std::vector<double> x;
  std::vector<double> y;       ///< lines, points, linespoints
  std::vector<double> y_low;   ///< band
  std::vector<double> y_high;  ///< band
  std::string color;           ///< "#rrggbb"; empty: gnuplot's default sequence
  double line_width = 1.5;
  int dash_type = 1;   ///< gnuplot dashtype: 1 solid, 2 dashed, 3 dotted, ...
  int point_type = 7;  ///< gnuplot point type (7: filled circle)
  double point_size = 0.6;
  double fill_opacity = 0.25;  ///< band
  bool y2 = false;             ///< drawn against the right-hand axis
  /// Whether the series' values set the automatic axis ranges (false for
  /// guide lines that should not stretch the plot).
  bool sets_range = true;
};

struct AxisRange {
  double low = 0.0;
  double high = 0.0;
};

struct Plot {
  std::string title;
  std::string x_label;   ///< with its unit, e.g. "frequency [Hz]"
  std::string y_label;   ///< with its unit
  std::string y2_label;  ///< right-hand axis (only when a series uses it)
  bool log_x = false;
  bool log_y = false;
  /// Equal decades on both (log) axes, see the header comment.
  bool equal_decades = false;
  double min_decade_ratio = 0.45;  ///< flattest aspect allowed with equal decades
  double max_decade_ratio = 1.6;   ///< tallest
  /// With equal decades: decades added above the data, room for a key at the top.
  int headroom_decades = 0;
  std::optional<AxisRange> x_range;  ///< default: from the series with sets_range
  std::optional<AxisRange> y_range;
  std::optional<AxisRange> y2_range;
  std::string key = "top right";  ///< gnuplot `set key` position, e.g. "bottom left"
  std::string key_font = ",10";   ///< the legend's font (gnuplot "name,size")
  std::vector<Series> series;
};

struct PlotOptions {
  /// The gnuplot executable: a name looked up in PATH or a path.
  std::string gnuplot = "gnuplot";
  int width_px = 720;
  int height_px = 480;
  std::string font = ",11";
  /// Prefix for the SVG's element ids (gnuplot names them the same in every
  /// plot; several SVGs inlined in one page need distinct ids). Empty: kept.
  std::string id_prefix;
};

struct PlotOutcome {
  std::optional<std::string> svg;  ///< the SVG element (no XML declaration)
  std::string error;               ///< why there is none (gnuplot missing, failed)
  bool gnuplot_missing = false;    ///< the executable could not be started
};

namespace detail {
/// The gnuplot script render_svg() runs (for the tests that read it; not a
/// stable interface).
std::string gnuplot_script(const Plot& plot, const PlotOptions& options = {});
}  // namespace detail

/// Runs gnuplot on the plot's script and returns its SVG, or an error.
/// Never throws for a missing or failing gnuplot.
PlotOutcome render_svg(const Plot& plot, const PlotOptions& options = {});

/// Whether `gnuplot` can be started (runs `gnuplot --version`).
bool gnuplot_available(const std::string& gnuplot = "gnuplot");

/// A string as a gnuplot single-quoted string literal: 'it''s'.
std::string gnuplot_quote(const std::string& text);

}  // namespace foglab::report
