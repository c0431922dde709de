// foglab CLI — the subcommands.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace foglab::cli {

/// Each registers its subcommand on `app` and returns the action to run when
/// the subcommand was chosen.
std::function<void()> register_analyze(CLI::App& app);
std::function<void()> register_batch(CLI::App& app);
std::function<void()> register_allan(CLI::App& app);
std::function<void()> register_fit(CLI::App& app);
std::function<void()> register_calibrate(CLI::App& app);
std::function<void()> register_rate_table(CLI::App& app);
std::function<void()> register_psd(CLI::App& app);
std::function<void()> register_generate(CLI::App& app);
std::function<void()> register_lab2_data(CLI::App& app);
std::function<void()> register_lab2(CLI::App& app);
std::function<void()> register_coil(CLI::App& app);
std::function<void()> register_simulate(CLI::App& app);
std::function<void()> register_sweep(CLI::App& app);
std::function<void()> register_lab1(CLI::App& app);

}  // namespace foglab::cli
