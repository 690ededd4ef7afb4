#include "stress_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <filesystem>

#include "cli_common.hpp"
#include "locations.hpp"
#include "option_values.hpp"
#include "output_files.hpp"
#include "steps_and_times.hpp"
#include "interrupt.hpp"
#include "motus/scene_error.hpp"
#include "motus/scene_file/scene_file.hpp"
#include "motus/scene_file/spelling.hpp"
#include "motus/simulation.hpp"
#include "progress_bar.hpp"
#include "stress_page.hpp"

namespace fs = std::filesystem;

namespace motus::cli {
namespace {

std::string number(double x) {
  if (std::isinf(x)) return "inf";
  return fmt::format("{:.3g}", x);
}

void print_tables(const stress::Report& r) {
  using namespace stress;
  fmt::print("{}: {} {}, {}-D, dt = {:g} s; sections: {}\n", r.scene_name, r.bodies, r.bodies == 1 ? "body" : "bodies", r.dimensions, r.dt,
             r.sections.empty() ? std::string("none") : fmt::format("{}", fmt::join(r.sections, ", ")));
  for (const auto& [section, why] : r.not_applied) fmt::print("  not measured: {}: {}\n", section, why);
  for (const auto& [integrator, why] : r.cannot_run) fmt::print("  cannot run it: {}: {}\n", integrator, why);
  const auto blown = fmt::format("blown up: not finite, |E - E0| > {:g} |E0|, or a bound orbit escaping or swing going over the top",
                                 r.settings.energy_factor);
  if (!r.stability.empty()) {
    fmt::print("\nlargest stable step ({} steps a trial; {})\n", r.settings.steps, blown);
    fmt::print("  {:<20}{:>14}{:>11}  {}\n", "integrator", "largest h", r.omega ? "omega h" : "", "theory (measured/theory)");
    for (const auto& s : r.stability) {
      if (!s.skipped.empty()) {
        fmt::print("  {:<20}{}\n", info(s.integrator).name, s.skipped);
        continue;
      }
      const double z = r.omega ? *r.omega * s.limit : 0;
      fmt::print("  {:<20}{:>14}{:>11}  {}{}{}\n", info(s.integrator).name, s.limit > 0 ? fmt::format("{:.7g}", s.limit) : "none",
                 r.omega && s.limit > 0 ? fmt::format("{:.6f}", z) : "", s.theory.text,
                 s.theory.z > 0 && s.limit > 0 ? fmt::format(" ({:.6f})", z / s.theory.z) : "",
                 // (the search's top, as the page says: a step that large still did not blow up)
                 s.limit > 0 && s.first_blowup == 0 ? " (no blow-up found: the largest h tried)" : "");
    }
  }
  if (!r.drift.empty()) {
    fmt::print("\ndrift over {} steps of {:g} s: largest |E - E0|/|E0|\n", r.settings.drift_steps, r.dt);
    fmt::print("  {:<20}{:>14}{:>14}  {}\n", "integrator", "first 1 %", "last 10 %", "verdict");
    for (const auto& d : r.drift)
      if (d.skipped.empty())
        fmt::print("  {:<20}{:>14}{:>14}  {}\n", info(d.integrator).name, number(d.first_hundredth_max),
                   d.blown.empty() ? number(d.last_tenth_max) : "-", d.verdict);
      else
        fmt::print("  {:<20}{}\n", info(d.integrator).name, d.skipped);
  }
  if (!r.stiffness.empty()) {
    fmt::print("\nstiffness: {} raised by decades at dt = {:g} s; the first factor that fails\n", r.stiffness_knob, r.dt);
    for (const auto& s : r.stiffness) {
      if (!s.skipped.empty()) {
        fmt::print("  {:<20}{}\n", info(s.integrator).name, s.skipped);
        continue;
      }
      const double t = theory_first_failure(r, s.integrator);
      fmt::print("  {:<20}{:>10}{}\n", info(s.integrator).name, s.first_failure > 0 ? fmt::format("{:g}", s.first_failure) : "none",
                 r.omega ? fmt::format("   theory {}", t > 0 ? fmt::format("{:g}", t) : "none") : "");
    }
  }
  // (A failure is "failed (k)" in its cell and note k below the table, as on the page.)
  auto print_notes = [](const FailureNotes& notes) {
    for (size_t k = 0; k < notes.notes().size(); ++k) fmt::print("  ({}) {}\n", k + 1, notes.notes()[k]);
  };
  if (!r.mass_ratio.empty()) {
    FailureNotes notes;
    fmt::print("\nmass ratio 1:R: a head-on pair against the formula{}\n",
               r.mass_ratio_scene ? ", and the scene with every second body R times heavier (its ball-ball contacts)" : "");
    fmt::print("  {:<18}{:>8}{:>14}{:>14}{:>14}", "integrator", "R", "pair |dv|/u", "pair energy", "pair momentum");
    if (r.mass_ratio_scene) fmt::print("{:>16}  {}", "scene contacts", "scene |dE|/E0");
    fmt::print("\n");
    for (const auto& m : r.mass_ratio) {
      const bool pair = m.pair.failed.empty();
      fmt::print("  {:<18}{:>8g}{:>14}{:>14}{:>14}", info(m.integrator).name, m.ratio,
                 pair ? number(m.pair.velocity_error) : notes.cell(m.pair.failed), pair ? number(m.pair.energy_error) : "-",
                 pair ? number(m.pair.momentum_error) : "-");
      if (r.mass_ratio_scene) {
        // (A run in which no balls met measured no collision: a 0 there looked perfect.)
        const std::string energy = !m.gas_failed.empty()    ? notes.cell(m.gas_failed)
                                   : m.gas_collisions == 0 ? "no contact in the run"
                                                           : number(m.gas_energy_error);
        fmt::print("{:>16}  {}", m.gas_collisions, energy);
      }
      fmt::print("\n");
    }
    print_notes(notes);
  }
  if (!r.speed.empty()) {
    FailureNotes notes;
    fmt::print("\nspeed: radii per step; the pair must never pass through each other{}\n",
               !r.speed_scene         ? ""
               : r.speed_container ? "; the scene's balls must stay in their box"
                                   : "; the scene's balls (no container)");
    fmt::print("  {:<18}{:>8}{:>12}{:>10}", "integrator", "radii", "pair order", "pair box");
    if (r.speed_scene) fmt::print("{}{:>10}{:>14}", r.speed_container ? fmt::format("{:>10}", "outside") : "", "overlap", "scene |dE|/E0");
    fmt::print("\n");
    for (const auto& s : r.speed) {
      const bool pair = s.pair_failed.empty();
      fmt::print("  {:<18}{:>8g}{:>12}{:>10}", info(s.integrator).name, s.radii_per_step,
                 !pair ? notes.cell(s.pair_failed) : s.pair_order_kept ? "kept" : "TUNNELLED", !pair ? "-" : s.pair_inside ? "yes" : "NO");
      if (r.speed_scene) {
        if (s.gas_failed.empty())
          fmt::print("{}{:>10}{:>14}", r.speed_container ? fmt::format("{:>10}", s.gas_outside) : "", number(s.gas_max_overlap),
                     number(s.gas_energy_error));
        else
          fmt::print("  {}", notes.cell(s.gas_failed));
      }
      fmt::print("\n");
    }
    print_notes(notes);
  }
  if (!r.sticks.empty()) {
    fmt::print("\nsticks between masses 1 and R (verlet): the largest stick error over {:g} s\n", r.settings.duration);
    FailureNotes notes;
    for (const auto& s : r.sticks)
      fmt::print("  {:<20}{:>8g}{:>12}\n", s.variant, s.ratio, s.failed.empty() ? number(s.max_error) : notes.cell(s.failed));
    print_notes(notes);
  }
}

}  // namespace

CLI::App* add_stress_command(CLI::App& app, StressOptions& o) {
  auto* c = app.add_subcommand("stress",
                               "The stability stress test of a scene: the largest stable step of each integrator against "
                               "theory, the long-run energy drift, stiffness, mass ratios, speed and sticks (as apply); "
                               "prints tables and writes a page (index.html, CSV, SVG and PNG plots)");
  c->add_option("scene", o.scene, "Scene file, or the name of a shipped scene (see `motus list`)")->required();
  add_list_option(c, "--integrators", o.integrators,
                  "Comma-separated integrators (default: every one that can run the scene)");
  c->add_option("--set", o.sets, "Override a scene field (repeatable), e.g. --set forces[0].stiffness=4")->type_name("PATH=VALUE");
  c->add_option("--out", o.out, "The page's folder (default: a new folder under runs/); must not exist yet")->check(folder_path());
  c->add_option("--steps", o.steps, "Steps of each stability and stiffness trial")->transform(whole_number_in(100, 10000000))->capture_default_str();
  c->add_option("--drift-steps", o.drift_steps, "Steps of the long run, 100 to 10^8 (10^7 takes about a second per integrator on one body)")
      ->transform(whole_number_in(100, 100000000))
      ->capture_default_str();
  c->add_option("--energy-factor", o.energy_factor, "Blown up: |E - E0| beyond this many times |E0|")->capture_default_str();
  c->add_option("--duration", o.duration,
                "Simulated seconds of each mass-ratio and sticks run (at most the scene's); a mass-ratio run whose balls "
                "have not met by then runs on until this long after they do")
      ->capture_default_str();
  return c;
}

int stress_command(const StressOptions& o) {
  const std::string path = resolve_scene_path(o.scene);
  const SceneDescription scene = load_scene(path, o.sets);
  if (!scene.mechanical)
    throw InputError(path + ": is a first-order system (\"" + scene.first_order->type +
                     "\"); stress measures the energy, contacts and sticks of bodies (motus bench precision measures a "
                     "system's accuracy)");
  if (!(o.energy_factor > 1) || !std::isfinite(o.energy_factor)) throw InputError("--energy-factor: must be a finite number > 1");
  if (!(o.duration > 0) || !std::isfinite(o.duration)) throw InputError("--duration: must be a finite number > 0");
  checked_step_count(static_cast<double>(o.drift_steps) * scene.dt, scene.dt, "--drift-steps");
  // (--duration is at most the scene's: the runs take no more, and a larger one is no fault of dt. A
  // mass-ratio run whose balls meet late may take the scene's whole duration.)
  const double longest = std::max(static_cast<double>(std::max(o.steps, o.drift_steps)) * scene.dt, scene.duration);
  check_time_resolution(scene.start_time, longest, scene.dt, path + ": start_time", path + ": dt");
  check_position_resolution(scene, scene.dt, path, path + ": dt");

  std::vector<Integrator> asked;
  if (o.integrators.empty()) {
    for (const auto& i : all_integrators()) asked.push_back(i.id);
  } else {
    for (const auto& n : o.integrators) {
      const auto id = integrator_from_name(n);
      if (!id)
        throw InputError("--integrators: " + unknown_one_of("integrator", n, integrator_names()));
      if (std::find(asked.begin(), asked.end(), *id) == asked.end()) asked.push_back(*id);
    }
  }

  stress::Report report;
  report.scene_name = scene.name;
  report.scene_file = path;
  report.description = scene.description;
  const auto& m = *scene.mechanical;
  report.dimensions = m.dimensions;
  report.bodies = static_cast<long>(m.bodies.size());
  report.dt = scene.dt;
  // (--duration is at most the scene's: what the runs take is what the report says)
  report.settings = {o.steps, o.drift_steps, o.energy_factor, std::min(o.duration, scene.duration)};
  report.omega = stress::harmonic_omega(scene);
  report.stiffness_knob = stress::stiffness_knob(scene);

  std::vector<Integrator> runs;  // the asked integrators that can run this scene
  for (Integrator i : asked) {
    try {
      Simulation check(scene, i);
      runs.push_back(i);
    } catch (const SceneError& e) {
      if (!o.integrators.empty()) report.cannot_run.emplace_back(info(i).name, e.what());
    }
  }
  long balls = 0;
  for (const auto& b : m.bodies) balls += b.radius > 0;
  const bool sticks = !m.sticks.empty() || !m.pins.empty();
  const bool contacts = !m.colliders.empty() || balls >= 2;
  auto among = [&](std::initializer_list<Integrator> which) {
    std::vector<Integrator> v;
    for (Integrator i : runs)
      if (std::find(which.begin(), which.end(), i) != which.end()) v.push_back(i);
    return v;
  };
  const std::string energy_why = sticks ? "the scene has sticks or pins, whose projection is dissipative: its energy is not an integrator's"
                                        : "the scene has contacts: between them every step is symplectic Euler's or Verlet's drift";
  // A damper or drag takes energy out by design: the drift would measure the physics.
  const bool dissipative =
      std::any_of(m.forces.drag.begin(), m.forces.drag.end(), [](const LinearDrag& d) { return d.coefficient != 0; }) ||
      std::any_of(m.forces.springs.begin(), m.forces.springs.end(), [](const Spring& s) { return s.damping != 0; });
  report.loses_energy_by_design = dissipative;
  // Without a frequency (what stiffness raises) the motion has no bound, and its energy grows with
  // the run whatever the step: where --steps steps first pass the factor is then no stability limit.
  // (free_fall's explicit Euler: 10.6 s in 10⁴ steps, 33.7 s in 10³; projectile_drag, whose drag
  // bounds the speed but not the fall: 20.0 s in 10⁴ steps, 4.2 s in 10⁵.)
  const bool frequency = !report.stiffness_knob.empty();
  if (!contacts && !sticks) {
    if (frequency)
      report.sections = {"stability"};
    else
      report.not_applied.emplace_back("stability", "the motion has no frequency and no bound (uniform gravity has no "
                                                   "frequency): its energy grows with the run whatever the step, so where "
                                                   "--steps steps first pass the factor is no stability limit");
    if (dissipative)
      report.not_applied.emplace_back("drift", "the scene loses energy by design (a damper or drag): its energy's change "
                                               "is the physics, not the integrator's");
    else
      report.sections.push_back("drift");
    if (!report.stiffness_knob.empty())
      report.sections.push_back("stiffness");
    else
      report.not_applied.emplace_back("stiffness", "the scene has no spring, orbit (central or mutual gravity) or pendulum "
                                                   "to stiffen (uniform gravity has no frequency)");
    report.not_applied.emplace_back("mass_ratio", "the scene has no contacts or sticks between bodies");
    report.not_applied.emplace_back("speed", "the scene has no balls or walls to tunnel through");
    report.not_applied.emplace_back("sticks", "the scene has no sticks");
  } else {
    for (const char* s : {"stability", "drift", "stiffness"}) report.not_applied.emplace_back(s, energy_why);
    if (contacts && !sticks) {
      report.sections = {"mass_ratio", "speed"};
      report.not_applied.emplace_back("sticks", "the scene has no sticks");
      // Parts of these sections that would measure nothing are listed, not printed as numbers.
      if (balls < 2) {
        report.mass_ratio_scene = false;
        report.not_applied.emplace_back("mass_ratio (the scene)", std::string(m.bodies.size() == 1 ? "one body" : "fewer than two balls") +
                                                                      ": a mass ratio needs two bodies that can meet (the pair still measures it)");
      }
      if (std::all_of(m.bodies.begin(), m.bodies.end(), [](const BodyDescription& b) {
            return std::all_of(b.velocity.begin(), b.velocity.end(), [](double v) { return v == 0; });
          })) {
        report.speed_scene = false;
        report.not_applied.emplace_back("speed (the scene)", "no body moves at the start: there is no speed to scale "
                                                             "(the pair still measures tunnelling)");
      } else if (m.colliders.boxes.empty()) {
        report.speed_container = false;
        report.not_applied.emplace_back("speed (balls outside their container)", "no container: the scene has no box");
      }
    } else {
      report.sections = {"sticks"};
      report.not_applied.emplace_back("mass_ratio", "covered by the sticks section: its sticks join masses 1 and R");
      report.not_applied.emplace_back("speed", "the scene's sticks and pins, not its contacts, are what it stresses");
    }
  }
  const auto contact_integrators = among({Integrator::SymplecticEuler, Integrator::Verlet});
  const bool verlet = !among({Integrator::Verlet}).empty();
  // (An adaptive method chooses its own steps: the force sections, which vary the step, measure none.)
  const bool fixed_step = std::any_of(runs.begin(), runs.end(), [](Integrator i) { return !info(i).adaptive; });
  if ((sticks && !verlet) || (contacts && !sticks && contact_integrators.empty()) || (!contacts && !sticks && !fixed_step))
    throw InputError(path + ": none of the integrators asked for can run the measurements that apply to this scene" +
                     (report.cannot_run.empty() ? "" : " (" + report.cannot_run.front().first + ": " + report.cannot_run.front().second + ")"));
  // A variant of the sticks section that would make no stick join masses 1 and R, or the same
  // bodies heavier as another, is listed, not run: stick_pendulum's bob is the one free body, its
  // pivot pinned, and every row read 2.2e-16, its two variants the same bob.
  if (sticks) {
    std::vector<std::pair<std::string, std::string>> skipped;
    std::vector<std::string> earlier;
    for (const auto& variant : stress::stick_variants()) {
      const std::string why = stress::stick_variant_not_measured(scene, variant, earlier);
      earlier.push_back(variant);
      if (why.empty())
        report.stick_variants_measured.push_back(variant);
      else
        skipped.emplace_back(variant, why);
    }
    if (report.stick_variants_measured.empty()) {
      report.sections.clear();
      std::string why;
      for (const auto& [variant, reason] : skipped) why += (why.empty() ? "" : "; ") + variant + ": " + reason;
      report.not_applied.emplace_back("sticks", why);
    } else {
      for (const auto& [variant, why] : skipped) report.not_applied.emplace_back("sticks (" + variant + ")", why);
    }
  }
  // The sections whose runs last --duration (at most the scene's).
  const bool timed_runs = std::find_if(report.sections.begin(), report.sections.end(), [](const std::string& s) {
                            return s == "mass_ratio" || s == "sticks";
                          }) != report.sections.end();
  // (As run, compare and bench refuse a run of no step: 1e-300 gave mass-ratio runs of none.)
  if (timed_runs && std::min(o.duration, scene.duration) < scene.dt)
    throw InputError(fmt::format("--duration: {:g} s is less than one step of dt = {:g} s: the mass-ratio and sticks runs "
                                 "would take no step", std::min(o.duration, scene.duration), scene.dt));

  const bool default_folder = o.out.empty();
  const std::string folder = default_folder ? default_run_folder("stress", scene.name) : o.out;
  if (!default_folder && output_exists(folder)) throw InputError(folder + ": already exists; stress never overwrites a page (choose another --out)");
  PartialFolder partial(folder, default_folder);

  // The work, for the progress bar: a unit per integrator and section (or per row), each weighed by the
  // steps it takes, as settings and the scene set them. (All alike, a drift run of 5·10⁷ steps weighed
  // as much as a stability search of a few hundred thousand: the bar went to 37 % in 2 s, then crawled
  // to its end with "~3 s to go".) A unit of several runs from t = 0 (a stability search's trials, a
  // stiffness sweep's factors) counts them as they start again.
  const auto& settings = report.settings;
  const double run_steps = std::max(1.0, std::min(settings.duration, scene.duration) / scene.dt);
  struct Unit {
    double weight;  // steps
    double runs;    // runs from t = 0 that it takes, about
  };
  const auto unit_of = [&](const std::string& section) -> Unit {
    // (A search for the stability limit: about 10 doublings and 24 halvings of its bracket.)
    if (section == "stability") return {34.0 * static_cast<double>(settings.steps), 34};
    if (section == "stiffness")
      return {static_cast<double>(stress::stiffness_factors().size() * static_cast<size_t>(settings.steps)),
              static_cast<double>(stress::stiffness_factors().size())};
    if (section == "drift") return {static_cast<double>(settings.drift_steps), 1};
    // A mass ratio's pair (8 steps), then with the scene its run of --duration; a speed's pair (at most
    // 1,000 steps), then with the scene its gas (at most 300).
    if (section == "mass_ratio") return report.mass_ratio_scene ? Unit{8 + run_steps, 2} : Unit{8, 1};
    if (section == "speed") return report.speed_scene ? Unit{1300, 2} : Unit{1000, 1};
    return {run_steps, 1};  // sticks: a run of --duration
  };
  double units = 0;
  for (const auto& s : report.sections) {
    const double count = s == "mass_ratio" ? static_cast<double>(contact_integrators.size() * stress::mass_ratios().size())
                         : s == "speed"    ? static_cast<double>(contact_integrators.size() * stress::speeds().size())
                         : s == "sticks"   ? static_cast<double>(report.stick_variants_measured.size() * stress::mass_ratios().size())
                                           : static_cast<double>(runs.size());
    units += count * unit_of(s).weight;
  }
  ProgressBar progress(0, units, "stress " + scene.name, 256);
  Unit unit{1, 1};
  double done = 0;       // the weight of the units done
  double within = 0;     // how far into the unit under way, 0 to 1
  double runs_done = 0, last_fraction = 0;  // of the unit under way's runs
  const stress::Tick tick = [&](double fraction) {
    fraction = std::clamp(fraction, 0.0, 1.0);
    if (fraction < last_fraction) ++runs_done;  // (a run from t = 0 again)
    last_fraction = fraction;
    within = std::max(within, std::min(1.0, (runs_done + fraction) / unit.runs));
    progress.update(done + unit.weight * within);
  };
  // (Each unit done is shown at once: the bar showed only the units done when the next one ticked,
  // and stopped short, at 64 %, when the last ones had no step left to tick.)
  auto unit_done = [&] {
    done += unit.weight;
    within = 0, runs_done = 0, last_fraction = 0;
    progress.update(done);
  };
  for (const auto& section : report.sections) {
    unit = unit_of(section);
    if (section == "stability")
      for (Integrator i : runs) report.stability.push_back(stress::measure_stability(scene, i, settings, tick)), unit_done();
    if (section == "drift")
      for (Integrator i : runs) report.drift.push_back(stress::measure_drift(scene, i, settings, tick)), unit_done();
    if (section == "stiffness")
      for (Integrator i : runs) report.stiffness.push_back(stress::measure_stiffness(scene, i, settings, tick)), unit_done();
    if (section == "mass_ratio")
      for (Integrator i : contact_integrators)
        for (double ratio : stress::mass_ratios())
          report.mass_ratio.push_back(stress::measure_mass_ratio(scene, i, ratio, settings, report.mass_ratio_scene, tick)), unit_done();
    if (section == "speed")
      for (Integrator i : contact_integrators)
        for (double s : stress::speeds()) report.speed.push_back(stress::measure_speed(scene, i, s, report.speed_scene, tick)), unit_done();
    if (section == "sticks")
      for (const auto& variant : report.stick_variants_measured)
        for (double ratio : stress::mass_ratios()) report.sticks.push_back(stress::measure_sticks(scene, variant, ratio, settings, tick)), unit_done();
  }
  progress.finish();
  stop_if_interrupted();

  const std::string warning = stress::write_page(partial.path(), report);
  stop_if_interrupted();
  const std::string written = partial.complete();  // (a default folder's name may have taken a number)
  print_tables(report);
  // (The runs take at most the scene's duration: one asked for longer is said, not clamped in silence.)
  if (timed_runs && o.duration > scene.duration)
    fmt::print("\n--duration {:g} s is more than the scene's {:g} s: its runs took {:g} s\n", o.duration, scene.duration,
               scene.duration);
  fmt::print("\npage: {}/index.html\n", written);
  if (!warning.empty()) tell("motus: {}\n", warning);
  return 0;
}

}  // namespace motus::cli
