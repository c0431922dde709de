// foglab — text helpers shared by the one-recording report (report.cc) and
// the lab-2 report (lab2.cc). Not installed.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "foglab/model/analysis.h"

namespace foglab::report::detail {

/// 4 significant digits; "-" for NaN or infinity.
std::string g(double v);
/// The same, "not visible" when there is no reading.
std::string g(const std::optional<double>& v);

/// Value and interval of a parameter as the reports show them: a resolved
/// term "v" and "[lo, hi]"; a term left out "< bound" and "[0, bound]".
struct ParameterText {
  std::string value, interval;
};
ParameterText parameter_text(const model::ParameterEstimate& p);

/// "a Wiener process (rate random walk), K = ... deg/h/sqrt(s)" etc.
std::string random_bias_answer(const model::AnalysisResult& r);
/// "tactical (decided by ...; by bias instability ...; by ARW ...)".
std::string class_sentence(const model::AnalysisResult& r);

/// <td>/<th> with the text escaped.
std::string td(std::string_view text);
std::string th(std::string_view text);

/// The report pages' style sheet.
extern const char* const kCss;

}  // namespace foglab::report::detail
