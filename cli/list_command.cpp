#include "list_command.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "cli_common.hpp"
#include "motus/integrator_name.hpp"
#include "motus/systems/system_catalog.hpp"
#include "motus/scene_file/scene_file.hpp"

namespace motus::cli {

CLI::App* add_list_command(CLI::App& app) {
  return app.add_subcommand("list", "List the shipped scenes, the integrators and the first-order systems, one line each");
}

int list_command() {
  fmt::print("scenes (in {}):\n", scenes_directory());
  for (const auto& file : shipped_scenes()) {
    const std::string name = std::filesystem::path(file).stem().string();
    try {
      const SceneDescription s = load_scene(file);
      fmt::print("  {:<20} {}\n", name, s.description);
    } catch (const std::exception& e) {
      fmt::print("  {:<20} (cannot be loaded: {})\n", name, e.what());
    }
  }
  fmt::print("integrators:\n");
  for (const auto& i : all_integrators())
    fmt::print("  {:<20} order {}{}{}  {}\n", i.name, i.order, i.adaptive ? ", adaptive" : "",
               i.needs_mechanical ? ", mechanical scenes only" : "", i.description);
  fmt::print("first-order systems (\"system\": {{\"type\": ...}}):\n");
  for (const auto& s : first_order_systems()) fmt::print("  {:<20} {}\n", s.type, s.description);
  return 0;
}

}  // namespace motus::cli
