// foglab CLI — the JSON (the `analyze --json` contract of docs/json.md) and the Allan
// table CSV of one analysis, shared by `analyze` and `lab2`. Formatting
// only: the numbers come from model::analyze().
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "foglab/core/units.h"
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

/// The analysis of an accelerometer channel in the accelerometer's terms:
/// analysis_json()'s document with every deg/h in its keys, units and
/// sentences in m/s^2 (`adev_deg_h` -> `adev_m_s2`, `psd_deg2_h2_per_hz` ->
/// `psd_m2_s4_per_hz`), the angle random walk replaced by the velocity
/// random walk, and the accuracy class null: the lab manual's Table 1 is a
/// table of gyroscopes.
nlohmann::json accelerometer_json(nlohmann::json gyro_form);

/// The noise parameters in the terms a navigation filter or Kalibr uses for
/// `sensor`, each with its unit in its name, continuous-time and per sample
/// at the record's rate (see report/imu.h for the conversions).
nlohmann::json sensor_terms_json(const model::AnalysisResult& result, Sensor sensor);

/// One fitted parameter: value, ci95 ([low, high], null when not closed),
/// status, upper_95 (as in `analyze --json`'s noise_model).
nlohmann::json parameter_estimate_json(const model::ParameterEstimate& p);

/// How the fit ended and the candidates it weighed (`analyze --json`'s fit).
nlohmann::json noise_fit_json(const model::NoiseFitResult& f, const model::NoiseFitOptions& o);

/// The Allan table of the residual with the fitted model and each term's part.
std::string analysis_csv(const model::AnalysisResult& result);

}  // namespace foglab::cli
