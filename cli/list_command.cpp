#include "list_command.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdlib>
#include <filesystem>

#include "cli_common.hpp"
#include "locations.hpp"
#include "plugin_loading.hpp"
#include "motus/integrate/integrator_catalog.hpp"
#include "motus/systems/system_catalog.hpp"
#include "motus/scene_file/scene_file.hpp"

namespace motus::cli {

CLI::App* add_list_command(CLI::App& app, std::vector<std::string>& plugin_files) {
  auto* list = app.add_subcommand(
      "list", "List the shipped scenes, the integrators and the first-order systems (and what --plugin brings), one line each");
  add_plugin_option(list, plugin_files);
  return list;
}

int list_command(const std::vector<std::string>& plugin_files) {
  load_plugins(plugin_files);
  if (std::error_code error; !std::filesystem::is_directory(scenes_directory(), error)) {
    const char* set = std::getenv("MOTUS_SCENES");
    throw InputError(scenes_directory() + ": the scenes' folder" + (set && *set ? " (MOTUS_SCENES)" : "") +
                     " is not a folder that can be read");
  }
  fmt::print("scenes (in {}):\n", scenes_directory());
  for (const auto& file : shipped_scenes()) {
    const std::string name = std::filesystem::path(file).stem().string();
    try {
      const SceneDescription s = load_scene(file);
      fmt::print("  {:<20} {}\n", name, one_line(s.description, 600));  // (one line each, whatever the file says)
    } catch (const std::exception& e) {
      fmt::print("  {:<20} (cannot be loaded: {})\n", name, one_line(e.what(), 600));
    }
  }
  fmt::print("integrators:\n");
  // (As wide as the longest name, a plug-in's included: student:symplectic-euler is 24.)
  size_t width = 20;
  for (const Method& m : plugins().integrators()) width = std::max(width, m.name().size());
  // The Verlet family and Yoshida's composition have their order for forces of the positions
  // alone: a damper or drag is evaluated at a velocity half a step old, and they fall to order 1
  // (docs/course.md, section 4; tests/test_order.cpp's DampedOrder).
  for (const auto& i : all_integrators())
    fmt::print("  {:<{}} order {}{}{}{}  {}\n", i.name, width, i.order,
               i.needs_mechanical && i.order > 1 ? " (1 with damping or drag)" : "", i.adaptive ? ", adaptive" : "",
               i.needs_mechanical ? ", mechanical scenes only" : "", i.description);
  for (const Method& m : plugins().integrators())
    fmt::print("  {:<{}} order {}{}{}  {}\n", m.name(), width, m.order(), m.adaptive() ? ", adaptive" : "",
               m.needs_mechanical() ? ", mechanical scenes only" : "", m.description());
  for (const auto& p : plugins().plugins()) {
    fmt::print("plug-in {} ({}): {}\n", p.name, p.file, p.description);
    fmt::print("  integrators: {}\n", p.integrator_names.empty() ? "none" : fmt::format("{}", fmt::join(p.integrator_names, ", ")));
    if (p.entry->collisions) fmt::print("  collision response: impulses and times of impact, in place of motus's\n");
    if (p.entry->constraints) fmt::print("  constraint projection: sticks, pins and walls, in place of motus's\n");
  }
  fmt::print("first-order systems (\"system\": {{\"type\": ...}}):\n");
  for (const auto& s : first_order_systems()) fmt::print("  {:<20} {}\n", s.type, s.description);
  fmt::print("  {:<20} {}\n", "equations",
             "your own: \"variables\", \"parameters\" and one expression per variable in \"equations\" "
             "(docs/scene-format.md)");
  return 0;
}

}  // namespace motus::cli
