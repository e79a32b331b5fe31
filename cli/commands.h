// Each subcommand registers its options on the app and, when chosen, sets `run`
// to the work it does, which returns the process's exit status (base/errors.h).
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

void add_info_command(CLI::App& app, std::function<int()>& run);
void add_gen_command(CLI::App& app, std::function<int()>& run);
void add_bench_command(CLI::App& app, std::function<int()>& run);
void add_compare_command(CLI::App& app, std::function<int()>& run);
void add_capacity_command(CLI::App& app, std::function<int()>& run);
void add_advise_command(CLI::App& app, std::function<int()>& run);
void add_check_command(CLI::App& app, std::function<int()>& run);
void add_diff_command(CLI::App& app, std::function<int()>& run);
void add_render_command(CLI::App& app, std::function<int()>& run);
void add_report_command(CLI::App& app, std::function<int()>& run);
