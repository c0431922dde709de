// foglab — text tables: CSV, TSV or whitespace-separated columns.
//
// Rules (also in reader.h):
//   * Lines whose first non-blank character is '#' are comments, and so is
//     the rest of a line after '#'; blank lines are skipped. "\n", "\r\n"
//     and "\r" endings, a UTF-8 byte-order mark and UTF-16 with a byte-order
//     mark (converted) are accepted; a NUL byte in the first block is
//     binary data. A line may hold 1 MiB, a table 10,000 columns.
//   * The delimiter is that of the first non-comment line: a tab if it has
//     one, else a semicolon if it has one, else a comma if it has one (not
//     with ReadOptions::decimal_comma, where "0,25" is a number), else runs
//     of spaces/tabs. Fields are trimmed, and one pair of surrounding double
//     quotes is removed.
//   * That first line is a header of names when any of its fields is not a
//     number; otherwise it is data and the columns are named "1", "2", ...
//   * Every row must have as many fields as the first line. Only the cells
//     of the columns that are read (the channel and, when it gives the
//     sample rate, the time column) are parsed, so a text column elsewhere
//     (a date, a status word) does not stop the reading.
// The file is read in blocks, so memory is the chosen column(s) only; the
// numbers are parsed with std::from_chars.
#include <fmt/format.h>
#include <iconv.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/core/text.h"
#include "readers_internal.h"

namespace foglab::io::internal {
namespace {

// Reads a file or standard input line by line through one buffer, within
// bounds: a line may hold at most kMaxLineBytes, and the first block read
// decides what the file is — text with "\n", "\r\n" or "\r" line ends,
// UTF-16 with a byte-order mark (converted to UTF-8 with iconv), or binary
// data (a NUL byte, a MAT or HDF5 signature), which is refused at once.
// The file and the converter are owned by their members, so that they are
// closed when the constructor throws (a binary or HDF5 file refused on its
// first block), which runs no destructor: each refused file had left its
// descriptor open, and a long run (the fuzzer's) ran out of them.
class LineReader {
 public:
  explicit LineReader(const std::string& path) : path_(path) {
    if (path == "-") {
      file_ = stdin;
    } else {
      owned_file_.reset(std::fopen(path.c_str(), "rb"));
      if (owned_file_ == nullptr) {
        throw UsageError(fmt::format("cannot open '{}': {}", path, std::strerror(errno)));
      }
      file_ = owned_file_.get();
    }
    buffer_.resize(kBlockBytes);
    first_block();
  }
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  /// The next line without its end-of-line characters; false at the end.
  bool next(std::string_view& line) {
    while (true) {
      const char* start = buffer_.data() + begin_;
      const void* newline = std::memchr(start, line_end_, end_ - begin_);
      if (newline != nullptr) {
        const auto length = static_cast<std::size_t>(static_cast<const char*>(newline) - start);
        if (length > kMaxLineBytes) too_long();
        line = trim_cr(std::string_view(start, length));
        begin_ += length + 1;
        ++line_number_;
        return true;
      }
      if (eof_) {
        if (begin_ == end_) return false;
        line = trim_cr(std::string_view(start, end_ - begin_));
        begin_ = end_;
        ++line_number_;
        return true;
      }
      if (end_ - begin_ > kMaxLineBytes) too_long();
      fill();
    }
  }

  /// 1-based number of the line last returned.
  std::size_t line_number() const { return line_number_; }

 private:
  static constexpr std::size_t kBlockBytes = std::size_t{1} << 20;
  static constexpr std::size_t kMaxLineBytes = std::size_t{1} << 20;

  [[noreturn]] void too_long() const {
    throw_data_error(path_, fmt::format("line {} is longer than {} MiB: not a table of numbers",
                                        line_number_ + 1, kMaxLineBytes >> 20));
  }

  static std::string_view trim_cr(std::string_view line) {
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
  }

  // What the file is, from its first block.
  void first_block() {
    raw_.resize(kBlockBytes);
    std::size_t got = read_raw(raw_.data(), raw_.size());
    raw_.resize(got);
    const std::string_view head(reinterpret_cast<const char*>(raw_.data()), got);
    const bool le = head.starts_with("\xFF\xFE");
    if (le || head.starts_with("\xFE\xFF")) {
      const iconv_t converter = iconv_open("UTF-8", le ? "UTF-16LE" : "UTF-16BE");
      if (converter == reinterpret_cast<iconv_t>(-1)) {
        throw_data_error(path_,
                         "the file is UTF-16 text, which this system cannot convert: "
                         "save it as UTF-8");
      }
      converter_.reset(converter);
      raw_.erase(raw_.begin(), raw_.begin() + 2);
      convert();
    } else {
      if (head.starts_with("\x89HDF") || (got > 516 && head.substr(512, 4) == "\x89HDF")) {
        throw_data_error(path_,
                         "this is an HDF5 file, not text: a MAT v7.3 file needs the extension "
                         ".mat or the format mat; other HDF5 files cannot be read (export the "
                         "data as CSV)");
      }
      if (head.starts_with("MATLAB ") && head.find("MAT-file") != std::string_view::npos) {
        throw_data_error(path_,
                         "this is a MAT file, not text: give it the extension .mat or the "
                         "format mat");
      }
      if (head.find('\0') != std::string_view::npos) {
        const std::size_t at = head.find('\0');
        throw_data_error(path_, fmt::format("byte {} is a NUL: binary data, not text (a raw "
                                            "record needs the extension .f32/.f64 or the "
                                            "format f32/f64, a MAT file the extension .mat or "
                                            "the format mat)",
                                            at + 1));
      }
      std::memcpy(buffer_.data(), raw_.data(), got);
      end_ = got;
      raw_.clear();
      if (got == 0) eof_ = true;
    }
    // Old Mac text: line ends are "\r" only.
    const std::string_view text(buffer_.data(), end_);
    if (text.find('\n') == std::string_view::npos && text.find('\r') != std::string_view::npos) {
      line_end_ = '\r';
    }
  }

  std::size_t read_raw(unsigned char* out, std::size_t size) {
    const std::size_t got = std::fread(out, 1, size, file_);
    if (got < size && std::ferror(file_)) {
      throw_data_error(path_, fmt::format("read error: {}", std::strerror(errno)));
    }
    return got;
  }

  // UTF-16 -> UTF-8 for what raw_ holds; an incomplete character waits.
  void convert() {
    char* in = reinterpret_cast<char*>(raw_.data());
    std::size_t in_left = raw_.size();
    char* out = buffer_.data() + end_;
    std::size_t out_left = buffer_.size() - end_;
    const std::size_t result = iconv(converter_.get(), &in, &in_left, &out, &out_left);
    if (result == static_cast<std::size_t>(-1) && errno == EILSEQ) {
      throw_data_error(path_,
                       fmt::format("the UTF-16 text is not valid near line {}", line_number_ + 1));
    }
    end_ = static_cast<std::size_t>(out - buffer_.data());
    raw_.erase(raw_.begin(), raw_.end() - static_cast<std::ptrdiff_t>(in_left));
  }

  void fill() {
    // Keep the unfinished line, grow if it fills the buffer, read more.
    std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
    if (buffer_.size() - end_ < kBlockBytes / 2) buffer_.resize(buffer_.size() * 2);
    if (converter_ == nullptr) {
      const std::size_t got =
          read_raw(reinterpret_cast<unsigned char*>(buffer_.data() + end_), buffer_.size() - end_);
      if (got == 0) eof_ = true;
      end_ += got;
      return;
    }
    // At most 3 bytes of UTF-8 per 2 bytes of UTF-16: read what fits.
    const std::size_t kept = raw_.size();
    const std::size_t want = (buffer_.size() - end_) / 2;
    raw_.resize(kept + want);
    const std::size_t got = read_raw(raw_.data() + kept, want);
    raw_.resize(kept + got);
    const std::size_t before = end_;
    convert();  // also what an earlier call had no room for
    if (got == 0 && end_ == before) {
      if (!raw_.empty()) {
        throw_data_error(path_, "the UTF-16 text ends in the middle of a character");
      }
      eof_ = true;
    }
  }

  struct ConverterCloser {
    void operator()(iconv_t converter) const { iconv_close(converter); }
  };

  std::string path_;
  FilePtr owned_file_;
  std::FILE* file_ = nullptr;  // owned_file_, or standard input
  std::vector<char> buffer_;
  std::vector<unsigned char> raw_;  // UTF-16 bytes not yet converted
  std::unique_ptr<std::remove_pointer_t<iconv_t>, ConverterCloser> converter_;
  char line_end_ = '\n';
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
  bool eof_ = false;
  std::size_t line_number_ = 0;
};

enum class Delimiter { comma, tab, semicolon, whitespace };

bool is_blank(char c) { return c == ' ' || c == '\t'; }

std::string_view trim(std::string_view text) {
  while (!text.empty() && is_blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_blank(text.back())) text.remove_suffix(1);
  return text;
}

std::string_view clean_field(std::string_view field) {
  field = trim(field);
  if (field.size() >= 2 && field.front() == '"' && field.back() == '"') {
    field = trim(field.substr(1, field.size() - 2));
  }
  return field;
}

// The content of a line: without a '#' comment and surrounding blanks.
std::string_view content_of(std::string_view line) {
  const auto hash = line.find('#');
  if (hash != std::string_view::npos) line = line.substr(0, hash);
  return trim(line);
}

// Calls visit(index, field) for each field; returns the number of fields.
template <typename Visit>
std::size_t split(std::string_view line, Delimiter delimiter, Visit&& visit) {
  std::size_t count = 0;
  if (delimiter == Delimiter::whitespace) {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && is_blank(line[i])) ++i;
      if (i == line.size()) break;
      const std::size_t first = i;
      while (i < line.size() && !is_blank(line[i])) ++i;
      visit(count++, clean_field(line.substr(first, i - first)));
    }
    return count;
  }
  const char separator = delimiter == Delimiter::comma       ? ','
                         : delimiter == Delimiter::semicolon ? ';'
                                                             : '\t';
  std::size_t first = 0;
  while (true) {
    const auto next = line.find(separator, first);
    if (next == std::string_view::npos) {
      visit(count++, clean_field(line.substr(first)));
      return count;
    }
    visit(count++, clean_field(line.substr(first, next - first)));
    first = next + 1;
  }
}

// Parses a whole field as a double (also "nan", "inf"; a leading '+').
bool parse_number(std::string_view field, double& value);

// The field with its one decimal comma made a point ("0,25" -> "0.25"), if
// it has exactly one comma, between two digits, and no point; else nullopt
// ("1," of "1, 2, 3" is no decimal comma).
std::optional<std::string> comma_to_point(std::string_view field) {
  const auto comma = field.find(',');
  auto digit = [&](std::size_t i) {
    return i < field.size() && std::isdigit(static_cast<unsigned char>(field[i])) != 0;
  };
  if (comma == std::string_view::npos || comma == 0 || !digit(comma - 1) || !digit(comma + 1) ||
      field.find(',', comma + 1) != std::string_view::npos ||
      field.find('.') != std::string_view::npos) {
    return std::nullopt;
  }
  std::string out(field);
  out[comma] = '.';
  return out;
}

// A number written with a decimal comma ("0,25", "-1,5e-3").
bool parse_comma_number(std::string_view field, double& value) {
  const std::optional<std::string> pointed = comma_to_point(field);
  return pointed && parse_number(*pointed, value);
}

bool parse_number(std::string_view field, double& value) {
  const char* first = field.data();
  const char* last = first + field.size();
  if (first != last && *first == '+') {
    ++first;
    if (first != last && (*first == '-' || *first == '+')) return false;
  }
  if (first == last) return false;
  const auto result = std::from_chars(first, last, value);
  if (result.ptr != last) return false;
  if (result.ec == std::errc::result_out_of_range) {
    // 1e999 -> inf, 1e-999 -> 0, as strtod does (the finite check follows)
    value = std::strtod(std::string(first, last).c_str(), nullptr);
    return true;
  }
  return result.ec == std::errc();
}

// The place value of a number's last printed digit ("0.125" -> 0.001,
// "1.5e-3" -> 1e-4, "12" -> 1): the rounding step of printed times. One
// pass over the field; called for every row that gives the time.
double printed_resolution(std::string_view field) {
  static constexpr std::array<double, 17> kTenths = {1.0,   1e-1,  1e-2,  1e-3,  1e-4,  1e-5,
                                                     1e-6,  1e-7,  1e-8,  1e-9,  1e-10, 1e-11,
                                                     1e-12, 1e-13, 1e-14, 1e-15, 1e-16};
  int decimals = 0;
  bool after_point = false;
  std::size_t i = 0;
  for (; i < field.size(); ++i) {
    const char c = field[i];
    if (c == '.') {
      after_point = true;
    } else if (c == 'e' || c == 'E') {
      break;
    } else if (after_point && c >= '0' && c <= '9') {
      ++decimals;
    }
  }
  if (i == field.size() && decimals < static_cast<int>(kTenths.size())) {
    return kTenths[static_cast<std::size_t>(decimals)];
  }
  int exponent = 0;
  if (i < field.size()) {
    const char* first = field.data() + i + 1;
    const char* last = field.data() + field.size();
    if (first != last && *first == '+') ++first;
    std::from_chars(first, last, exponent);
  }
  return std::pow(10.0, exponent - decimals);
}

// The first content line of a table and what it says about the columns.
struct Layout {
  Delimiter delimiter = Delimiter::whitespace;
  bool has_header = false;
  std::vector<std::string> names;  // header names, or "1", "2", ...
  std::string first_line;          // kept when it is data
  std::size_t first_line_number = 0;
};

std::string shorten(std::string_view text);

// The most columns a table may have (a line of 1 MiB could hold half a
// million); a wider one is not a recording.
constexpr std::size_t kMaxColumns = 10000;

// Whether `content` reads as two or more numbers with decimal commas
// separated by blanks or semicolons ("0,01 1,25", "0,01;1,25"): then the
// commas are not the delimiter.
bool looks_like_decimal_commas(std::string_view content) {
  if (content.find(',') == std::string_view::npos) return false;
  const Delimiter delimiter =
      content.find(';') != std::string_view::npos ? Delimiter::semicolon : Delimiter::whitespace;
  bool all = true;
  std::size_t with_comma = 0;
  const std::size_t count = split(content, delimiter, [&](std::size_t, std::string_view field) {
    double ignored = 0.0;
    if (parse_comma_number(field, ignored)) {
      ++with_comma;
    } else if (!parse_number(field, ignored)) {
      all = false;
    }
  });
  // One field ("0,5") is as much two integer columns: read as before.
  return all && with_comma > 0 && count > 1;
}

std::optional<Layout> read_layout(const std::string& path, LineReader& reader, bool decimal_comma) {
  std::string_view line;
  bool first = true;
  while (reader.next(line)) {
    if (first && line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);
    first = false;
    const std::string_view content = content_of(line);
    if (content.empty()) continue;
    const bool binary = std::any_of(content.begin(), content.end(), [](char c) {
      return static_cast<unsigned char>(c) < 0x20 && c != '\t';
    });
    if (binary) {
      throw_data_error(path, fmt::format("line {} holds binary data, not text: a raw record "
                                         "needs the extension .f32/.f64 or the format f32/f64, "
                                         "a MAT file the extension .mat or the format mat",
                                         reader.line_number()));
    }
    const bool tab = content.find('\t') != std::string_view::npos;
    const bool semicolon = content.find(';') != std::string_view::npos;
    if (!decimal_comma && !tab && looks_like_decimal_commas(content)) {
      throw_data_error(path, fmt::format("line {} ('{}') reads as numbers with decimal commas: "
                                         "give ReadOptions::decimal_comma to read them so",
                                         reader.line_number(), shorten(content)));
    }
    Layout layout;
    layout.delimiter = tab                                           ? Delimiter::tab
                       : semicolon                                   ? Delimiter::semicolon
                       : decimal_comma                               ? Delimiter::whitespace
                       : content.find(',') != std::string_view::npos ? Delimiter::comma
                                                                     : Delimiter::whitespace;
    std::vector<std::string> fields;
    const std::size_t count =
        split(content, layout.delimiter, [&](std::size_t k, std::string_view field) {
          if (k < kMaxColumns) fields.emplace_back(field);
        });
    if (count > kMaxColumns) {
      throw_data_error(path, fmt::format("line {} has {} columns; a table may have at most {}",
                                         reader.line_number(), count, kMaxColumns));
    }
    for (const std::string& field : fields) {
      double ignored = 0.0;
      const bool number = decimal_comma
                              ? parse_comma_number(field, ignored) || parse_number(field, ignored)
                              : parse_number(field, ignored);
      if (!number) layout.has_header = true;
    }
    for (std::size_t k = 0; k < fields.size(); ++k) {
      const bool named = layout.has_header && !fields[k].empty();
      layout.names.push_back(named ? fields[k] : std::to_string(k + 1));
    }
    if (!layout.has_header) layout.first_line = std::string(content);
    layout.first_line_number = reader.line_number();
    return layout;
  }
  return std::nullopt;
}

std::string column_label(const Layout& layout, std::size_t index) {
  if (!layout.has_header) return fmt::format("column {}", index + 1);
  return fmt::format("column {} ({})", index + 1, layout.names[index]);
}

std::string column_listing(const Layout& layout) {
  return join_names(layout.names) + (layout.has_header ? "" : " (no header)");
}

// A column chosen by header name (exact, else ignoring case) or 1-based index.
std::size_t find_column(const std::string& path, const Layout& layout, const std::string& wanted,
                        std::string_view role) {
  if (layout.has_header) {
    for (std::size_t k = 0; k < layout.names.size(); ++k) {
      if (layout.names[k] == wanted) return k;
    }
    for (std::size_t k = 0; k < layout.names.size(); ++k) {
      if (ascii_lower(layout.names[k]) == ascii_lower(wanted)) return k;
    }
  }
  const bool digits = !wanted.empty() && std::all_of(wanted.begin(), wanted.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c)) != 0;
  });
  if (digits) {
    const unsigned long index = std::strtoul(wanted.c_str(), nullptr, 10);
    if (index >= 1 && index <= layout.names.size()) return index - 1;
    throw_data_error(path, fmt::format("no {} column {}: the table has {} column(s){}", role,
                                       wanted, layout.names.size(),
                                       layout.has_header ? " (" + join_names(layout.names) + ")"
                                                         : std::string()));
  }
  throw_data_error(
      path, fmt::format("no {} column '{}'; columns: {}", role, wanted, column_listing(layout)));
}

std::optional<std::size_t> find_time_column(const std::string& path, const Layout& layout,
                                            const ReadOptions& options) {
  if (!options.time_channel.empty()) {
    return find_column(path, layout, options.time_channel, "time");
  }
  if (!layout.has_header) return std::nullopt;
  for (std::size_t k = 0; k < layout.names.size(); ++k) {
    if (is_time_channel_name(layout.names[k], NameMatch::ignore_case)) return k;
  }
  return std::nullopt;
}

std::size_t choose_column(const std::string& path, const Layout& layout, const ReadOptions& options,
                          std::optional<std::size_t> time) {
  if (!options.channel.empty()) return find_column(path, layout, options.channel, "channel");
  if (layout.names.size() == 1) return 0;
  std::vector<std::size_t> candidates;
  for (std::size_t k = 0; k < layout.names.size(); ++k) {
    if (k != time) candidates.push_back(k);
  }
  if (candidates.size() == 1) return candidates.front();
  if (layout.has_header) {
    for (std::string_view preferred : kDefaultDataChannels) {
      for (std::size_t k : candidates) {
        if (ascii_lower(layout.names[k]) == ascii_lower(preferred)) return k;
      }
    }
  }
  throw_data_error(path, fmt::format("several columns ({}) and none is Y1 or rate: choose one "
                                     "with ReadOptions::channel (a name or a 1-based index)",
                                     column_listing(layout)));
}

std::string shorten(std::string_view text) {
  if (text.size() <= 40) return std::string(text);
  return std::string(text.substr(0, 37)) + "...";
}

}  // namespace

Series read_text(const std::string& path, const ReadOptions& options) {
  LineReader reader(path);
  const std::optional<Layout> found = read_layout(path, reader, options.decimal_comma);
  if (!found) throw_data_error(path, "no data (the file is empty or has only comments)");
  const Layout& layout = *found;

  const std::optional<std::size_t> time = find_time_column(path, layout, options);
  const std::size_t column = choose_column(path, layout, options, time);
  if (!options.sample_rate_hz && !time) {
    throw UsageError(
        fmt::format("{} has no sample rate (no time column t, time or time_s): "
                    "give ReadOptions::sample_rate_hz",
                    quoted_path(path)));
  }
  const bool need_time = !options.sample_rate_hz;
  const bool separate_time = need_time && *time != column;
  const std::size_t columns = layout.names.size();

  Series series;
  series.path = path;
  series.channel = layout.names[column];
  series.available_channels = layout.names;
  series.variables = layout.names;
  std::optional<TimeAxisCheck> time_check;
  if (need_time) time_check.emplace(path, layout.names[*time], 0.0);
  // Room for the rows the file's size suggests, judged by the first data
  // row, so that the vectors rarely grow (and never double) on the way.
  const double file_bytes = static_cast<double>(regular_file_size(path).value_or(0));
  auto reserve_for = [&](std::string_view first_row) {
    const double rows = file_bytes / static_cast<double>(first_row.size() + 1);
    const auto capacity = static_cast<std::size_t>(rows * 1.2) + 16;
    series.values.reserve(capacity);
    advise_huge_pages(series.values.data(), series.values.capacity());
  };

  auto parse_cell = [&](std::string_view field, std::size_t index, std::size_t line_number) {
    double value = 0.0;
    if (parse_number(field, value)) return value;
    if (options.decimal_comma && parse_comma_number(field, value)) return value;
    // An empty cell of the channel is a missing sample, as a spreadsheet or
    // pandas writes one (a time cell is never missing).
    if (field.empty() && options.nan_is_missing && index == column)
      return std::numeric_limits<double>::quiet_NaN();
    if (field.empty()) {
      throw_data_error(
          path, fmt::format("line {}, {} is empty", line_number, column_label(layout, index)));
    }
    const bool comma = !options.decimal_comma && parse_comma_number(field, value);
    throw_data_error(path, fmt::format("line {}, {}: '{}' is not a number{}", line_number,
                                       column_label(layout, index), shorten(field),
                                       comma ? " (a decimal comma: give "
                                               "ReadOptions::decimal_comma to read it so)"
                                             : ""));
  };
  auto take_row = [&](std::string_view content, std::size_t line_number) {
    if (series.values.empty() && file_bytes > 0) reserve_for(content);
    std::string_view value_field;
    std::string_view time_field;
    const std::size_t count =
        split(content, layout.delimiter, [&](std::size_t k, std::string_view field) {
          if (k == column) value_field = field;
          if (separate_time && k == *time) time_field = field;
        });
    if (count != columns) {
      throw_data_error(path, fmt::format("line {} has {} column(s), expected {} as in line {}{}",
                                         line_number, count, columns, layout.first_line_number,
                                         layout.has_header ? " (" + join_names(layout.names) + ")"
                                                           : std::string()));
    }
    if (options.max_samples && series.values.size() == *options.max_samples) {
      throw_data_error(path, fmt::format("more than {} samples (at line {}): the limit for one "
                                         "record (ReadOptions::max_samples)",
                                         *options.max_samples, line_number));
    }
    series.values.push_back(parse_cell(value_field, column, line_number));
    if (need_time) {
      const std::string_view field = separate_time ? time_field : value_field;
      time_check->add(separate_time ? parse_cell(field, *time, line_number) : series.values.back(),
                      line_number, printed_resolution(field));
    }
  };

  if (!layout.has_header) take_row(layout.first_line, layout.first_line_number);
  std::string_view line;
  while (reader.next(line)) {
    const std::string_view content = content_of(line);
    if (!content.empty()) take_row(content, reader.line_number());
  }
  if (series.values.empty()) {
    throw_data_error(
        path, fmt::format("the file has a header ({}) but no data rows", join_names(layout.names)));
  }

  if (need_time) {
    apply_time_axis(series, time_check->result(), layout.names[*time], /*rate_from_axis=*/true);
  }
  return series;
}

std::vector<std::string> list_text_channels(const std::string& path) {
  LineReader reader(path);
  const std::optional<Layout> layout = read_layout(path, reader, /*decimal_comma=*/false);
  if (!layout) throw_data_error(path, "no data (the file is empty or has only comments)");
  return layout->names;
}

}  // namespace foglab::io::internal
