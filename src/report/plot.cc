// foglab — the gnuplot driver (plot.h): script writing and a pipe to gnuplot.
#include "foglab/report/plot.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <string_view>
#include <tuple>
#include <utility>

extern char** environ;

namespace foglab::report {
namespace {

// ---- running a program with its stdin, stdout and stderr on pipes ---------

struct ProcessResult {
  bool started = false;
  int spawn_error = 0;   ///< errno of the failed start
  int exit_status = -1;  ///< exit code, or -1 when killed by a signal
  std::string out, err;
};

void close_fd(int& fd) {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

/// Runs argv[0] (looked up in PATH unless it holds a '/'), writes `input` to
/// its standard input and collects its standard output and error, all
/// through one poll() loop so that neither side can block the other.
/// SIGPIPE (gnuplot exiting before reading everything) is blocked in this
/// thread while writing and a pending one consumed, so it never kills the
/// caller.
ProcessResult run_process(const std::vector<std::string>& args, std::string_view input) {
  ProcessResult result;
  int in[2] = {-1, -1}, out[2] = {-1, -1}, err[2] = {-1, -1};
  if (::pipe2(in, O_CLOEXEC) != 0 || ::pipe2(out, O_CLOEXEC) != 0 || ::pipe2(err, O_CLOEXEC) != 0) {
    result.spawn_error = errno;
    for (int* p : {in, out, err}) {
      close_fd(p[0]);
      close_fd(p[1]);
    }
    return result;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, in[0], 0);
  posix_spawn_file_actions_adddup2(&actions, out[1], 1);
  posix_spawn_file_actions_adddup2(&actions, err[1], 2);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  // The child starts with no signal blocked and the default actions: the
  // command line blocks SIGINT/SIGTERM/SIGHUP for its own interrupt thread
  // and ignores SIGPIPE/SIGXFSZ (core/output.h), which gnuplot must not
  // inherit.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  for (const int s : {SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGXFSZ}) sigaddset(&defaults, s);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  pid_t pid = -1;
  const int rc = ::posix_spawnp(&pid, argv[0], &actions, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  close_fd(in[0]);
  close_fd(out[1]);
  close_fd(err[1]);
  if (rc != 0) {
    result.spawn_error = rc;
    close_fd(in[1]);
    close_fd(out[0]);
    close_fd(err[0]);
    return result;
  }
  result.started = true;

  sigset_t sigpipe, old_mask;
  sigemptyset(&sigpipe);
  sigaddset(&sigpipe, SIGPIPE);
  sigset_t pending;
  sigemptyset(&pending);
  sigpending(&pending);
  const bool sigpipe_was_pending = sigismember(&pending, SIGPIPE) == 1;
  pthread_sigmask(SIG_BLOCK, &sigpipe, &old_mask);
  bool got_epipe = false;

  ::fcntl(in[1], F_SETFL, ::fcntl(in[1], F_GETFL) | O_NONBLOCK);
  std::size_t written = 0;
  if (input.empty()) close_fd(in[1]);
  char buffer[65536];
  while (in[1] >= 0 || out[0] >= 0 || err[0] >= 0) {
    pollfd fds[3];
    int n = 0;
    int idx_in = -1, idx_out = -1, idx_err = -1;
    if (in[1] >= 0) fds[idx_in = n++] = {in[1], POLLOUT, 0};
    if (out[0] >= 0) fds[idx_out = n++] = {out[0], POLLIN, 0};
    if (err[0] >= 0) fds[idx_err = n++] = {err[0], POLLIN, 0};
    if (::poll(fds, static_cast<nfds_t>(n), -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    if (idx_in >= 0 && fds[idx_in].revents != 0) {
      const ssize_t w = ::write(in[1], input.data() + written, input.size() - written);
      if (w > 0) {
        written += static_cast<std::size_t>(w);
        if (written == input.size()) close_fd(in[1]);
      } else if (w < 0 && errno != EAGAIN && errno != EINTR) {
        if (errno == EPIPE) got_epipe = true;
        close_fd(in[1]);
      }
    }
    for (auto [idx, fd, text] :
         {std::tuple{idx_out, &out[0], &result.out}, std::tuple{idx_err, &err[0], &result.err}}) {
      if (idx < 0 || fds[idx].revents == 0) continue;
      const ssize_t r = ::read(*fd, buffer, sizeof buffer);
      if (r > 0) {
        text->append(buffer, static_cast<std::size_t>(r));
      } else if (r == 0 || (errno != EAGAIN && errno != EINTR)) {
        close_fd(*fd);
      }
    }
  }
  close_fd(in[1]);
  close_fd(out[0]);
  close_fd(err[0]);

  if (got_epipe && !sigpipe_was_pending) {
    const timespec zero{0, 0};
    while (::sigtimedwait(&sigpipe, nullptr, &zero) < 0 && errno == EINTR) {
    }
  }
  pthread_sigmask(SIG_SETMASK, &old_mask, nullptr);

  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  result.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// ---- the script ------------------------------------------------------------

bool usable(double v, bool log_axis) { return std::isfinite(v) && (!log_axis || v > 0.0); }

struct Extent {
  double low = std::numeric_limits<double>::infinity();
  double high = -std::numeric_limits<double>::infinity();
  void add(double v) {
    low = std::min(low, v);
    high = std::max(high, v);
  }
  bool valid() const { return low <= high; }
};

std::string number(double v) { return fmt::format("{:.9g}", v); }

/// One datablock's rows, with a blank line (a break in the curve) for a
/// point that cannot be drawn; empty when no point can.
std::string datablock_rows(const Series& s, bool log_x, bool log_y) {
  std::string rows;
  bool any = false, broken = false;
  const bool band = s.style == SeriesStyle::band;
  const std::size_t n = band ? std::min({s.x.size(), s.y_low.size(), s.y_high.size()})
                             : std::min(s.x.size(), s.y.size());
  for (std::size_t k = 0; k < n; ++k) {
    const bool ok =
        usable(s.x[k], log_x) &&
        (band ? usable(s.y_low[k], log_y) && usable(s.y_high[k], log_y) : usable(s.y[k], log_y));
    if (!ok) {
      broken = any;
      continue;
    }
    if (broken) rows += "\n";
    broken = false;
    any = true;
    rows += band
                ? fmt::format("{} {} {}\n", number(s.x[k]), number(s.y_low[k]), number(s.y_high[k]))
                : fmt::format("{} {}\n", number(s.x[k]), number(s.y[k]));
  }
  return rows;
}

void add_extent(const Series& s, bool log_x, bool log_y, Extent& x, Extent& y) {
  const bool band = s.style == SeriesStyle::band;
  const std::size_t n = band ? std::min({s.x.size(), s.y_low.size(), s.y_high.size()})
                             : std::min(s.x.size(), s.y.size());
  for (std::size_t k = 0; k < n; ++k) {
    if (!usable(s.x[k], log_x)) continue;
    if (band) {
      if (!usable(s.y_low[k], log_y) || !usable(s.y_high[k], log_y)) continue;
      y.add(s.y_low[k]);
      y.add(s.y_high[k]);
    } else {
      if (!usable(s.y[k], log_y)) continue;
      y.add(s.y[k]);
    }
    x.add(s.x[k]);
  }
}

/// Whole decades [lo, hi] (exponents) covering an extent.
std::pair<int, int> decades(const Extent& e) {
  int lo = static_cast<int>(std::floor(std::log10(e.low) + 1e-9));
  int hi = static_cast<int>(std::ceil(std::log10(e.high) - 1e-9));
  if (hi <= lo) hi = lo + 1;
  return {lo, hi};
}

/// Adds `extra` decades to [lo, hi], the larger half at the low end.
void widen(std::pair<int, int>& d, int extra) {
  d.second += extra / 2;
  d.first -= extra - extra / 2;
}

std::string range_text(double lo, double hi) {
  return fmt::format("[{}:{}]", number(lo), number(hi));
}

/// A linear axis range with a small margin (gnuplot's autoscale would stretch
/// to the guide lines too).
std::pair<double, double> padded(const Extent& e, double fraction) {
  double span = e.high - e.low;
  if (!(span > 0.0)) span = std::max(std::abs(e.high), 1.0) * 0.1;
  return {e.low - fraction * span, e.high + fraction * span};
}

std::string sanitize(const std::string& text) {
  std::string out = text;
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  }
  return out;
}

std::string rewrite_ids(const std::string& svg, const std::string& prefix) {
  if (prefix.empty()) return svg;
  auto id_char = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-' || c == '.';
  };
  // The ids gnuplot defined.
  std::set<std::string> ids;
  for (std::size_t p = svg.find("id="); p != std::string::npos; p = svg.find("id=", p + 3)) {
    if (p == 0 || !std::isspace(static_cast<unsigned char>(svg[p - 1]))) continue;
    const std::size_t q = p + 3;
    if (q >= svg.size() || (svg[q] != '\'' && svg[q] != '"')) continue;
    const std::size_t end = svg.find(svg[q], q + 1);
    if (end == std::string::npos) break;
    ids.insert(svg.substr(q + 1, end - q - 1));
  }
  std::map<std::string, int> occurrences;
  std::string out;
  out.reserve(svg.size() + ids.size() * prefix.size() * 4);
  for (std::size_t p = 0; p < svg.size(); ++p) {
    const char c = svg[p];
    out += c;
    const bool id_attr = p >= 3 && (c == '\'' || c == '"') && svg.compare(p - 3, 3, "id=") == 0 &&
                         p >= 4 && std::isspace(static_cast<unsigned char>(svg[p - 4]));
    const bool reference =
        (c == '\'' || c == '"' || c == '(') && p + 1 < svg.size() && svg[p + 1] == '#';
    if (id_attr) {
      std::size_t e = p + 1;
      while (e < svg.size() && id_char(svg[e])) ++e;
      const std::string id = svg.substr(p + 1, e - p - 1);
      if (ids.count(id) != 0) {
        // gnuplot repeats some ids (an opaque key redraws the plots' samples):
        // the repeats get a suffix, references keep pointing at the first.
        const int seen = ++occurrences[id];
        out += prefix + id;
        if (seen > 1) out += fmt::format("_{}", seen);
        p = e - 1;
      }
    } else if (reference) {
      std::size_t e = p + 2;
      while (e < svg.size() && id_char(svg[e])) ++e;
      if (ids.count(svg.substr(p + 2, e - p - 2)) != 0) {
        out += '#';
        out += prefix;
        ++p;  // the '#'
      }
    }
  }
  return out;
}

/// The <svg> element alone: no XML declaration or DOCTYPE.
std::string strip_prolog(const std::string& svg) {
  const std::size_t start = svg.find("<svg");
  return start == std::string::npos ? svg : svg.substr(start);
}

}  // namespace

std::string gnuplot_quote(const std::string& text) {
  std::string out = "'";
  for (char c : sanitize(text)) {
    if (c == '\'') out += '\'';
    out += c;
  }
  out += '\'';
  return out;
}

std::string detail::gnuplot_script(const Plot& plot, const PlotOptions& options) {
  std::string s;
  s += fmt::format("set terminal svg size {},{} fixed font {} noenhanced background '#ffffff'\n",
                   options.width_px, options.height_px, gnuplot_quote(options.font));
  s += "set output\n";
  s += "set encoding utf8\n";

  // Data, one block per drawable series.
  std::vector<std::size_t> drawn;
  Extent x, y, y2;
  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    const Series& ser = plot.series[i];
    const bool log_y = ser.y2 ? false : plot.log_y;
    const std::string rows = datablock_rows(ser, plot.log_x, log_y);
    if (rows.empty()) continue;
    drawn.push_back(i);
    s += fmt::format("$d{} << EOD\n{}EOD\n", i, rows);
    if (ser.sets_range) add_extent(ser, plot.log_x, log_y, x, ser.y2 ? y2 : y);
  }

  if (!plot.title.empty()) s += fmt::format("set title {}\n", gnuplot_quote(plot.title));
  s += fmt::format("set xlabel {}\n", gnuplot_quote(plot.x_label));
  s += fmt::format("set ylabel {}\n", gnuplot_quote(plot.y_label));
  if (plot.log_x) s += "set logscale x 10\nset format x '%g'\nset mxtics 10\n";
  if (plot.log_y) s += "set logscale y 10\nset format y '%g'\nset mytics 10\n";
  s += "set grid xtics ytics lc rgb '#d0d0d0' lw 1 dt 1\n";
  if (plot.log_x || plot.log_y) {
    s += fmt::format("set grid {} {} lc rgb '#d0d0d0' lw 1 dt 1, lc rgb '#ececec' lw 1 dt 1\n",
                     plot.log_x ? "mxtics" : "", plot.log_y ? "mytics" : "");
  }
  s += fmt::format("set key {} opaque box lc rgb '#a0a0a0' samplen 2.5 font {}\n", plot.key,
                   gnuplot_quote(plot.key_font));

  // Ranges.
  if (plot.x_range) {
    x = {};
    x.add(plot.x_range->low);
    x.add(plot.x_range->high);
  }
  if (plot.y_range) {
    y = {};
    y.add(plot.y_range->low);
    y.add(plot.y_range->high);
  }
  if (plot.y2_range) {
    y2 = {};
    y2.add(plot.y2_range->low);
    y2.add(plot.y2_range->high);
  }
  const bool equal = plot.equal_decades && plot.log_x && plot.log_y && x.valid() && y.valid() &&
                     x.low > 0.0 && y.low > 0.0;
  if (equal) {
    auto dx = decades(x);
    auto dy = decades(y);
    dy.second += std::max(0, plot.headroom_decades);
    const int nx = dx.second - dx.first, ny = dy.second - dy.first;
    if (ny < plot.min_decade_ratio * nx) {
      widen(dy, static_cast<int>(std::ceil(plot.min_decade_ratio * nx - 1e-9)) - ny);
    } else if (ny > plot.max_decade_ratio * nx) {
      widen(dx, static_cast<int>(std::ceil(ny / plot.max_decade_ratio - 1e-9)) - nx);
    }
    s += fmt::format("set xrange {}\n",
                     range_text(std::pow(10.0, dx.first), std::pow(10.0, dx.second)));
    s += fmt::format("set yrange {}\n",
                     range_text(std::pow(10.0, dy.first), std::pow(10.0, dy.second)));
    s += fmt::format("set size ratio {}\n", number(static_cast<double>(dy.second - dy.first) /
                                                   static_cast<double>(dx.second - dx.first)));
  } else {
    if (x.valid()) {
      if (plot.x_range || !plot.log_x) {
        const auto [lo, hi] = plot.x_range ? std::pair{x.low, x.high} : padded(x, 0.0);
        s += fmt::format("set xrange {}\n", range_text(lo, hi));
      } else {
        s += fmt::format("set xrange {}\n", range_text(x.low, x.high));
      }
    }
    if (y.valid()) {
      if (plot.y_range) {
        s += fmt::format("set yrange {}\n", range_text(y.low, y.high));
      } else if (plot.log_y) {
        s += fmt::format("set yrange {}\n", range_text(y.low / 1.25, y.high * 1.25));
      } else {
        const auto [lo, hi] = padded(y, 0.05);
        s += fmt::format("set yrange {}\n", range_text(lo, hi));
      }
    }
  }
  const bool uses_y2 =
      std::any_of(drawn.begin(), drawn.end(), [&](std::size_t i) { return plot.series[i].y2; });
  if (uses_y2) {
    s += "set ytics nomirror\nset y2tics\n";
    s += fmt::format("set y2label {}\n", gnuplot_quote(plot.y2_label));
    if (y2.valid()) {
      const auto [lo, hi] = plot.y2_range ? std::pair{y2.low, y2.high} : padded(y2, 0.05);
      s += fmt::format("set y2range {}\n", range_text(lo, hi));
    }
  }

  // The plot command.
  std::string cmd;
  for (std::size_t i : drawn) {
    const Series& ser = plot.series[i];
    if (!cmd.empty()) cmd += ", \\\n     ";
    const std::string color =
        ser.color.empty() ? std::string() : fmt::format(" lc rgb {}", gnuplot_quote(ser.color));
    const std::string title = ser.title.empty() ? " notitle" : " title " + gnuplot_quote(ser.title);
    const std::string axes = ser.y2 ? " axes x1y2" : "";
    switch (ser.style) {
      case SeriesStyle::lines:
        cmd += fmt::format("$d{} using 1:2{} with lines lw {} dt {}{}{}", i, axes,
                           number(ser.line_width), ser.dash_type, color, title);
        break;
      case SeriesStyle::points:
        cmd += fmt::format("$d{} using 1:2{} with points pt {} ps {}{}{}", i, axes, ser.point_type,
                           number(ser.point_size), color, title);
        break;
      case SeriesStyle::linespoints:
        cmd += fmt::format("$d{} using 1:2{} with linespoints lw {} dt {} pt {} ps {}{}{}", i, axes,
                           number(ser.line_width), ser.dash_type, ser.point_type,
                           number(ser.point_size), color, title);
        break;
      case SeriesStyle::band:
        cmd +=
            fmt::format("$d{} using 1:2:3{} with filledcurves fs transparent solid {} noborder{}{}",
                        i, axes, number(ser.fill_opacity), color, title);
        break;
    }
  }
  if (cmd.empty()) {
    // Nothing drawable: an empty frame (gnuplot needs something to plot).
    s += "unset key\nplot [0:1] [0:1] NaN notitle\n";
  } else {
    s += "plot " + cmd + "\n";
  }
  s += "unset output\n";
  return s;
}

PlotOutcome render_svg(const Plot& plot, const PlotOptions& options) {
  PlotOutcome outcome;
  const ProcessResult r = run_process({options.gnuplot}, detail::gnuplot_script(plot, options));
  if (!r.started) {
    outcome.gnuplot_missing = true;
    outcome.error =
        fmt::format("cannot run '{}': {}", options.gnuplot, std::strerror(r.spawn_error));
    return outcome;
  }
  if (r.exit_status == 127 && r.out.empty()) {
    outcome.gnuplot_missing = true;
    outcome.error = fmt::format("cannot run '{}' (exit status 127)", options.gnuplot);
    return outcome;
  }
  const std::size_t close = r.out.rfind("</svg>");
  if (r.exit_status != 0 || r.out.find("<svg") == std::string::npos || close == std::string::npos) {
    std::string message = r.err;
    while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) {
      message.pop_back();
    }
    outcome.error = fmt::format("'{}' failed (exit status {}){}{}", options.gnuplot, r.exit_status,
                                message.empty() ? "" : ": ", message);
    return outcome;
  }
  outcome.svg = rewrite_ids(strip_prolog(r.out.substr(0, close + 6)), options.id_prefix);
  return outcome;
}

bool gnuplot_available(const std::string& gnuplot) {
  const ProcessResult r = run_process({gnuplot, "--version"}, {});
  return r.started && r.exit_status == 0 && r.out.find("gnuplot") != std::string::npos;
}

}  // namespace foglab::report
