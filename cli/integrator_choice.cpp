#include "integrator_choice.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "motus/integrate/integrator_catalog.hpp"
#include "motus/scene_file/spelling.hpp"
#include "motus/simulation.hpp"
#include "plugin_loading.hpp"

namespace motus::cli {

std::vector<std::string> known_integrators() {
  std::vector<std::string> names = integrator_names();
  for (const auto& m : plugins().integrators()) names.push_back(m.name());
  return names;
}

std::string whole_names(const std::vector<std::string>& names, size_t budget) {
  std::string list;
  for (size_t k = 0; k < names.size(); ++k) {
    const std::string next = (list.empty() ? "" : ", ") + names[k];
    // (Room is kept for saying how many follow, should the next one not fit.)
    const size_t after = names.size() - k - 1;
    const size_t more = after ? fmt::format(", …and {} more", after).size() : 0;
    if (list.size() + next.size() + more > budget)
      return list + (list.empty() ? "" : ", ") + fmt::format("…and {} more", names.size() - k);
    list += next;
  }
  return list;
}

size_t room_for_list(const std::string& before, const std::string& after) {
  constexpr size_t line = 400, least = 120;
  const size_t used = before.size() + after.size();
  return used + least > line ? least : line - used;
}

namespace {

std::string joined_with_and(const std::vector<std::string>& items) {
  std::string text;
  for (size_t k = 0; k < items.size(); ++k) text += (k == 0 ? "" : k + 1 == items.size() ? " and " : ", ") + items[k];
  return text;
}

// What a plug-in brings besides integrators (the parts that replace motus's own), in words, or "".
std::string plugin_parts_in_words(const LoadedPlugin& p) {
  std::vector<std::string> parts;
  if (p.entry->collisions) parts.emplace_back("collision rules");
  if (p.entry->constraints) parts.emplace_back("a constraint projection");
  return joined_with_and(parts);
}


// The message for an integrator that is neither built in nor a loaded plug-in's.
std::string unknown_integrator(const std::string& path, const std::string& name) {
  const std::string head = path + ": --integrator: unknown integrator \"" + name + "\"";
  const size_t colon = name.find(':');
  const std::vector<std::string> known = known_integrators();
  auto with_list = [&](const std::string& before, const std::vector<std::string>& names, const std::string& after) {
    return before + whole_names(names, room_for_list(before, after)) + after;
  };
  if (colon == std::string::npos) return with_list(head + did_you_mean(name, known) + " (known: ", known, ")");
  const std::string owner = name.substr(0, colon), own = name.substr(colon + 1);
  if (plugins().empty())
    return with_list(head + did_you_mean(name, known) + " (known: ", known,
                     "); " + owner + ":NAME integrators come from a plug-in, and none is loaded: load its plug-in with "
                                     "--plugin FILE.so");
  const LoadedPlugin* named = nullptr;
  for (const auto& p : plugins().plugins())
    if (p.name == owner) named = &p;
  if (named && named->integrator_names.empty()) {
    // (The course's plug-ins are all "student": the collisions one loaded for student:euler.)
    const std::string parts = plugin_parts_in_words(*named);
    return head + ": the plug-in " + named->file + " brings no integrators" +
           (parts.empty() ? "" : " (it brings " + parts + ")") +
           (owner == "student" ? "; the integrators assignment's plug-in does"
                               : "; load a plug-in that brings them with --plugin FILE.so");
  }
  if (named) {
    // Its own integrators, first and whole: the built-ins' names would crowd them out of the line.
    const std::string builtin = integrator_from_name(own) ? "; motus's own is --integrator " + own : "";
    return with_list(head + did_you_mean(name, named->integrator_names) + " (" + named->file + " brings ",
                     named->integrator_names, ")" + builtin);
  }
  std::vector<std::string> loaded;
  for (const auto& p : plugins().plugins()) loaded.push_back("\"" + p.name + "\" from " + p.file);
  return with_list(head + did_you_mean(name, known) + " (known: ", known,
                   "); no loaded plug-in is named \"" + owner + "\" (loaded: " + joined_with_and(loaded) + ")");
}

}  // namespace

std::string what_plugin_brings(const LoadedPlugin& plugin) {
  std::vector<std::string> brings;
  const auto& names = plugin.integrator_names;
  if (names.size() == 1) brings.push_back("an integrator (" + names.front() + ")");
  else if (names.size() == 2) brings.push_back("2 integrators (" + names[0] + ", " + names[1] + ")");
  else if (names.size() > 2)
    brings.push_back(fmt::format("{} integrators ({}, {}, …)", names.size(), names[0], names[1]));
  if (const std::string parts = plugin_parts_in_words(plugin); !parts.empty()) brings.push_back(parts);
  return brings.empty() ? "nothing" : joined_with_and(brings);
}

std::vector<std::string> unused_plugin_notes(const std::string& scene_name, const Method& method, const World* world) {
  std::vector<std::string> notes;
  for (const auto& p : plugins().plugins()) {
    const auto& names = p.integrator_names;
    const bool integrates = method.is_external() && std::find(names.begin(), names.end(), method.name()) != names.end();
    const bool collides = p.entry->collisions && world && world->has_collisions();
    const bool projects = p.entry->constraints && world && world->has_constraints();
    if (integrates || collides || projects) continue;
    std::vector<std::string> why;
    if (!names.empty())
      why.push_back("this run integrates with " + method.name() + " (--integrator " + p.name + ":NAME runs one of them)");
    if ((p.entry->collisions || p.entry->constraints) && !world)
      why.push_back(scene_name + " is a first-order system, with no bodies");
    if (p.entry->collisions && world)
      why.push_back(world->has_constraints() ? scene_name + " has no collision pass (on verlet its contacts are projected)"
                                             : scene_name + " has no collisions");
    if (p.entry->constraints && world)
      why.push_back(scene_name + " has no sticks or pins" +
                    (world->has_collisions() ? " (its contacts are collided, on " + method.name() +
                                                   "; --integrator verlet projects them)"
                                             : ""));
    notes.push_back("note: the plug-in " + p.file + " brings " + what_plugin_brings(p) +
                    (why.empty() ? "" : ", and " + joined_with_and(why)) + ": it is not used in this run");
  }
  return notes;
}

Method method_for(const std::string& path, const SceneDescription& scene, const std::optional<std::string>& requested) {
  const std::string name = requested.value_or(scene.integrator);
  std::optional<Method> method;
  if (const auto builtin = integrator_from_name(name)) method = *builtin;
  else method = plugins().integrator(name);
  if (!method) throw InputError(unknown_integrator(path, name));
  if (method->needs_mechanical() && !scene.is_mechanical()) {  // the file's own integrator was checked by the loader
    // A plug-in's step(x, v) need not be symplectic (a student's explicit Euler): it steps bodies.
    // What can run this scene: the built-in first-order methods, and the plug-ins' own.
    std::string first_order = first_order_integrator_names();
    for (const auto& m : plugins().integrators())
      if (!m.needs_mechanical()) first_order += ", " + m.name();
    throw InputError(path + ": --integrator: " + name +
                     (method->is_external() ? " steps bodies (x and v) and needs a mechanical scene (bodies), and this "
                                              "is a first-order system; use "
                                            : " is symplectic and needs a mechanical scene (bodies); use ") +
                     first_order);
  }
  return *method;
}

std::string non_finite_suspect(const Simulation& sim, const Method& method, const std::string& smaller_step) {
  if (const FirstOrderSystem* system = sim.first_order_system())
    if (std::string why = system->why_not_finite(); !why.empty()) return why;
  for (const auto& p : plugins().plugins()) {
    const auto& names = p.integrator_names;
    if (method.is_external() && std::find(names.begin(), names.end(), method.name()) != names.end())
      return "check the plug-in's integrator " + method.name() + " (" + p.file + "), or try " + smaller_step;
  }
  for (const auto& p : plugins().plugins())
    if (p.entry->collisions || p.entry->constraints)
      return "check the plug-in's " + std::string(p.entry->collisions ? "collision response" : "constraint projection") +
             " (" + p.file + "); else the integrator is unstable at this step";
  return "the integrator is unstable at this step; try " + smaller_step + " or another --integrator";
}

}  // namespace motus::cli
