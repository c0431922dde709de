// The record the noise fit's studies are about (allan_fit_bound,
// allan_fit_oracle): its white, flicker and random-walk terms, its sample
// rate and its length, as command-line options.
#pragma once

#include <CLI/CLI.hpp>

#include "foglab/core/noise_model.h"

namespace foglab::bench {

struct StudiedRecord {
  NoiseModel model;
  double fs_hz = 100.0;
  double hours = 2.0;
};

inline void add_record_options(CLI::App& app, StudiedRecord& record) {
  app.add_option("--N", record.model.N, "white noise [deg/h/sqrt(Hz)]")->required();
  app.add_option("--B", record.model.B, "flicker [deg/h]");
  app.add_option("--K", record.model.K, "random walk [deg/h/sqrt(s)]");
  app.add_option("--fs", record.fs_hz, "sample rate [Hz]");
  app.add_option("--hours", record.hours, "record length [h]");
}

}  // namespace foglab::bench
