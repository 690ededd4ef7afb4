#pragma once
// `motus list`: the shipped scenes, the integrators and the first-order systems,
// one line each.
#include <CLI/CLI.hpp>

namespace motus::cli {

CLI::App* add_list_command(CLI::App& app);
int list_command();

}  // namespace motus::cli
