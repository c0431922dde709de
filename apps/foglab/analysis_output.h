// foglab CLI — the JSON (the `analyze --json` contract of docs/json.md) and the Allan
// table CSV of one analysis, shared by `analyze` and `lab2`. Formatting
// only: the numbers come from model::analyze().
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "foglab/model/analysis.h"

namespace foglab::cli {

/// What the analysis does not know about its input.
struct AnalysisJsonInput {
  nlohmann::json input;              ///< input_json() of the rate's Series
  std::string temperature_channel;   ///< empty: none
  double record_mean_deg_h = 0.0;    ///< the constant bias when there is no temperature
  std::string units = "deg/h";       ///< the unit the rate was read in
  std::string temp_degree = "auto";  ///< as requested
  std::string taus = "octave";       ///< as requested
  std::vector<std::string> notes;    ///< the command's notes (before the analysis's)
};

/// The whole analysis as JSON (docs/json.md).
nlohmann::json analysis_json(const model::AnalysisResult& result, const AnalysisJsonInput& input,
                             const model::AnalysisOptions& options);

/// The Allan table of the residual with the fitted model and each term's part.
std::string analysis_csv(const model::AnalysisResult& result);

}  // namespace foglab::cli
