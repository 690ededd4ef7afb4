#pragma once
// `motus list`: the shipped scenes, the integrators and the first-order systems,
// one line each.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace motus::cli {

CLI::App* add_list_command(CLI::App& app, std::vector<std::string>& plugin_files);
int list_command(const std::vector<std::string>& plugin_files);

}  // namespace motus::cli
