#include "bench_precision_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string_view>

#include "cli_common.hpp"
#include "integrator_choice.hpp"
#include "locations.hpp"
#include "machine_load.hpp"
#include "option_values.hpp"
#include "output_files.hpp"
#include "plugin_loading.hpp"
#include "steps_and_times.hpp"
#include "interrupt.hpp"
#include "motus/compare/explanations.hpp"
#include "motus/exact/exact_solution.hpp"
#include "motus/precision/engine_peers.hpp"
#include "motus/precision/motus_sweep.hpp"
#include "motus/precision/odeint_peer.hpp"
#include "motus/precision/precision_report.hpp"
#include "motus/precision/targets.hpp"
#include "motus/precision/timing_rounds.hpp"
#include "motus/scene_file/scene_file.hpp"
#include "motus/scene_file/spelling.hpp"
#include "motus/simulation.hpp"
#include "progress_bar.hpp"

namespace fs = std::filesystem;

namespace motus::cli {
namespace {

const std::vector<std::string> kPeers = {"odeint", "box2d", "bullet"};

std::string microseconds(const std::optional<precision::Fastest>& f) {
  if (!f) return "-";
  return fmt::format("{}{:.3g} ({:.3g})", f->at.upper_bound ? "<=" : "", 1e6 * f->at.seconds, 1e6 * f->at.median_seconds);
}

}  // namespace

CLI::App* add_bench_precision_command(CLI::App& bench, BenchPrecisionOptions& o) {
  auto* p = bench.add_subcommand("precision", "Run time against error: sweep each integrator's step or tolerance, "
                                              "measure the final-time error against the scene's exact solution, and "
                                              "draw the work-precision diagrams into a run folder");
  p->add_option("scene", o.scene, "A scene with an exact or reference solution (spring, oscillator, kepler, pendulum, lorenz, ...)")
      ->required();
  add_list_option(p, "--integrators", o.integrators,
                  "Comma-separated integrators (default: every one; those that cannot run the scene are listed as such)");
  add_list_option(p, "--peers", o.peers,
                  "Comma-separated peers on the same problem: odeint (Boost.Odeint's steppers on the "
                  "same right-hand side), box2d, bullet (mechanical scenes, dt = 1/30 ... 1/960); default: none");
  p->add_option("--levels", o.levels, "Fixed-step methods: h = dt / 2^k for k = 0 ... N-1")->transform(whole_number_in(1, 20))->capture_default_str();
  p->add_option("--per-decade", o.per_decade, "Adaptive methods: tolerances 1e-3 ... 1e-13, this many per decade")
      ->transform(whole_number_in(1, 10))
      ->capture_default_str();
  p->add_option("--repeats", o.repeats, "Timed rounds, after one untimed round: each runs every point of every engine once, the engines taking "
                 "turns; a point's fastest run counts")
      ->transform(whole_number_in(1, 100))
      ->capture_default_str();
  add_list_option(p, "--targets", o.targets,
                  "Comma-separated target errors to read every curve at (default 1e-4 ... 1e-10)");
  p->add_option("--duration", o.duration, "End time (default: the scene's; for reference states, the last one within it)")
      ->transform(a_number());
  p->add_option("--set", o.sets, "Override a scene field (repeatable)")->type_name("PATH=VALUE");
  p->add_option("--out", o.out, "The run folder (default: a new folder under runs/); must not exist yet")->check(folder_path());
  CLI::Option* csv = p->add_option("--csv", o.csv, "Also write the table (precision.csv) here")->check(non_empty_path());
  p->add_flag("--overwrite", o.overwrite, "Allow --csv to replace an existing file")->needs(csv);
  add_plugin_option(p, o.plugins);
  return p;
}

int bench_precision_command(const BenchPrecisionOptions& o) {
  const std::string path = resolve_scene_path(o.scene);
  const SceneDescription scene = load_scene(path, o.sets);
  load_plugins(o.plugins);
  if (!has_exact_solution(scene))
    throw InputError(path + ": declares no \"exact\" solution or \"reference\" states to measure error against");
  if (o.duration && !(*o.duration > 0 && std::isfinite(*o.duration)))
    throw InputError("--duration: must be a finite number > 0");
  for (double target : o.targets)
    if (!(target > 0 && std::isfinite(target))) throw InputError("--targets: every target error must be a finite number > 0");
  for (const auto& peer : o.peers)
    if (std::find(kPeers.begin(), kPeers.end(), peer) == kPeers.end())
      throw InputError("--peers: " + unknown_one_of("peer", peer, {"odeint", "box2d", "bullet"}));

  if (o.duration) checked_step_count(*o.duration, scene.dt, "--duration");
  check_time_resolution(scene.start_time, o.duration.value_or(scene.duration), scene.dt, path + ": start_time",
                        o.duration ? "--duration" : path + ": dt/duration");
  check_position_resolution(scene, scene.dt, path, path + ": dt");
  double end = scene.start_time + o.duration.value_or(scene.duration);
  if (last_reference_time(scene)) {
    // Only the reference times are known: use the last one within the duration.
    double best = -INFINITY;
    for (const auto& r : scene.reference)
      if (r.t <= end + 1e-9) best = std::max(best, r.t);
    if (!std::isfinite(best)) throw InputError(fmt::format("{}: no reference state at or before t = {:g}", path, end));
    end = best;
  }

  std::vector<Method> chosen;
  if (o.integrators.empty()) {
    for (const auto& i : all_integrators()) chosen.emplace_back(i.id);
    for (const auto& m : plugins().integrators()) chosen.push_back(m);
  } else {
    for (const auto& name : o.integrators) {
      std::optional<Method> method;
      if (const auto id = integrator_from_name(name)) method.emplace(*id);
      else if (const auto m = plugins().integrator(name)) method = *m;
      else {
        // The known ones in whole names: a plug-in's eight took the list past main's line of 400
        // bytes, which cut it inside a name ("sympl…verlet"). Room as method_for leaves it.
        const std::vector<std::string> known = known_integrators();
        const std::string before =
            "--integrators: unknown integrator \"" + name + "\"" + did_you_mean(name, known) + " (known: ";
        throw InputError(before + whole_names(known, room_for_list(before, ")")) + ")");
      }
      // (each once, as stress takes them: rk4,rk4 is one curve)
      if (std::none_of(chosen.begin(), chosen.end(), [&](const Method& m) { return m.name() == method->name(); }))
        chosen.push_back(*method);
    }
  }
  auto wants = [&](const std::string& peer) { return std::find(o.peers.begin(), o.peers.end(), peer) != o.peers.end(); };

  // Everything that can be refused is refused before anything runs.
  const bool default_folder = o.out.empty();
  const std::string folder = default_folder ? default_run_folder("precision", scene.name) : o.out;
  // (`motus run --trajectory -` writes to standard output; here a file called "-" would be made.)
  if (o.csv == "-")
    throw InputError("--csv -: standard output is the table's; give the copy a file name (or use the run folder's "
                     "precision.csv)");
  if (!o.csv.empty()) {
    // The copy goes beside the run, not into it (the run's folder must not exist until it is whole).
    const fs::path csv = fs::absolute(o.csv).lexically_normal();
    fs::path run = fs::absolute(folder).lexically_normal();
    if (!run.has_filename()) run = run.parent_path();  // ("out/")
    const auto [end, _] = std::mismatch(run.begin(), run.end(), csv.begin(), csv.end());
    if (end == run.end()) throw InputError("--csv: " + o.csv + " is in the run's folder " + folder + "; put the copy elsewhere");
    check_can_write(o.csv, o.overwrite);
  }
  if (!default_folder && output_exists(folder)) throw InputError(folder + ": already exists; bench precision never overwrites a run (choose another --out)");
  PartialFolder partial(folder, default_folder);
  // A plug-in of which this sweep uses nothing says so, on standard error (standard output is the
  // table's): none of its integrators is among --integrators, or it brings none (its collision rules
  // and projection are never used here: bench precision takes only integrators from a plug-in), or
  // none of those chosen can run this scene (their curves say why).
  for (const auto& p : plugins().plugins()) {
    const auto& names = p.integrator_names;
    auto its_own = [&](const Method& m) { return m.is_external() && std::find(names.begin(), names.end(), m.name()) != names.end(); };
    const bool named = std::any_of(chosen.begin(), chosen.end(), its_own);
    if (std::any_of(chosen.begin(), chosen.end(), [&](const Method& m) {
          return its_own(m) && precision::why_motus_cannot_run(scene, m).empty();
        }))
      continue;
    std::string why;
    if (named) why = "none of its integrators chosen can run this scene (their curves say why)";
    else if (!names.empty()) why = "--integrators names none of its integrators (without --integrators each is swept)";
    if (p.entry->collisions || p.entry->constraints)
      why += (why.empty() ? "" : " and ") + std::string("bench precision takes only integrators from a plug-in");
    tell("note: the plug-in {} brings {}{}: it is not used in this run\n", p.file, what_plugin_brings(p),
         why.empty() ? "" : ", and " + why);
  }

  precision::Sweep sweep;
  sweep.end = end;
  sweep.dt = scene.dt;
  sweep.levels = o.levels;
  sweep.per_decade = o.per_decade;
  sweep.repeats = o.repeats;
  // The progress counts steps, not points: each fixed-step level has twice the steps of the one
  // before, and its last level is half of a method's work (counted in points, arenstorf's bar stood
  // at 15 % for a minute and a quarter of its 89 s, then ran to the end in a second). An adaptive
  // point is counted as a run at its first step, dt: a guess, as its steps are not known before.
  double fixed_work = 0, engine_work = 0;
  for (const double h : precision::fixed_steps(scene, sweep)) fixed_work += precision::nominal_steps(scene, sweep, h);
  for (const double h : precision::engine_steps()) engine_work += precision::nominal_steps(scene, sweep, h);
  const double adaptive_work =
      static_cast<double>(precision::tolerances(sweep).size()) * precision::nominal_steps(scene, sweep, scene.dt);
  // (What cannot run the scene does no work: five symplectic methods of a first-order system, counted,
  // left the bar at 40 % when the run ended.)
  double total = 0;
  for (const Method& m : chosen)
    if (precision::why_motus_cannot_run(scene, m).empty()) total += m.adaptive() ? adaptive_work : fixed_work;
  if (wants("odeint") && precision::why_motus_cannot_run(scene, Integrator::Rk4).empty())
    total += 2 * fixed_work + 2 * adaptive_work;
  for (const char* engine : {"box2d", "bullet"}) total += wants(engine) && scene.is_mechanical() ? engine_work : 0;
  // Every point runs once untimed, then once in each timed round (timing_rounds.hpp).
  const double rounds = 1 + sweep.repeats;
  total *= rounds;
  ProgressBar progress(0, total, "bench precision", 1);
  progress.without_estimate();  // (the steps to come cost more each than those done: no rate says what is left)
  double done = 0;
  sweep.point_done = [&](double steps) {
    progress.update(done += steps);
    stop_if_interrupted();
  };
  sweep.now_and_then = [] { stop_if_interrupted(); };

  // Each method's sweep; the peers' in the order asked for. What a peer cannot run is found as it runs
  // (in the untimed round): its work, counted in the total for every round, is then done.
  std::vector<precision::SweepOf> sweeps;
  for (const Method& method : chosen)
    sweeps.push_back([&scene, method](const precision::Sweep& s) { return std::vector{precision::sweep_motus(scene, method, s)}; });
  std::vector<std::string> versions = {"motus " MOTUS_VERSION};
  if (wants("odeint")) {
    sweeps.push_back([&](const precision::Sweep& s) {
      std::vector<precision::Curve> curves = precision::sweep_odeint(scene, s);
      for (const auto& c : curves)
        // (Odeint's symplectic method on a first-order system or with drag: found only as it runs.)
        if (s.round == 0 && !c.unsupported.empty() && precision::why_motus_cannot_run(scene, Integrator::Rk4).empty())
          progress.update(done += rounds * (c.adaptive ? adaptive_work : fixed_work));
      return curves;
    });
    versions.push_back(precision::odeint_version());
  }
  for (const char* engine : {"box2d", "bullet"}) {
    if (!wants(engine)) continue;
    sweeps.push_back([&, engine](const precision::Sweep& s) {
      precision::Curve c;
      if (!scene.is_mechanical()) {
        c.method = c.engine = engine;
        c.unsupported = "a first-order system: the engines model bodies";
        return std::vector{c};
      }
      c = precision::sweep_engine(scene, engine, s);
      if (s.round == 0 && !c.unsupported.empty()) progress.update(done += rounds * engine_work);  // (found only as it runs)
      return std::vector{c};
    });
  }
  // The machine's load as the sweeps begin and end (on a busy one the ratios may be off), as compare says it.
  compare::MachineLoad load;
  load.cores = online_cores();
  load.at_start = load_average();
  std::vector<precision::Curve> curves = precision::sweep_in_rounds(sweeps, sweep);
  load.at_end = load_average();
  for (const auto& c : curves)
    if ((c.engine == "box2d" || c.engine == "bullet") && !c.description.empty()) versions.push_back(c.description);
  progress.finish();

  // The points, method by method.
  fmt::print("run time against error: {} to t = {:g}; error = max |y - y_exact| over the state where each run ends (a fixed\n"
             "step's at its first step at or past t); seconds = CPU time, the fastest of {} timed rounds (after one untimed\n"
             "round), every engine in each round, taking turns\n\n",
             scene.name, end, o.repeats);
  fmt::print("{:<38}{:>11}{:>10}{:>13}{:>12}{:>12}\n", "integrator", "h / tol", "steps", "evaluations", "error", "seconds");
  for (const auto& c : curves) {
    if (!c.unsupported.empty()) {
      fmt::print("{:<38}  cannot run this scene: {}\n", c.method, c.unsupported);
      continue;
    }
    for (const auto& p : c.points) {
      if (!p.failed.empty()) {
        fmt::print("{:<38}{:>11.3g}  failed: {}\n", c.method, c.adaptive ? p.tolerance : p.h, one_line(p.failed, 120));
        continue;
      }
      fmt::print("{:<38}{:>11.3g}{:>10}{:>13}{:>12.3e}{:>12.3e}\n", c.method, c.adaptive ? p.tolerance : p.h, p.steps,
                 p.evaluations, p.error, p.seconds);
    }
  }

  // The targets table: the fastest of each engine at each target, and motus's against each peer's.
  const std::vector<double> targets = o.targets.empty() ? precision::default_targets() : o.targets;
  std::vector<std::string> engines = {"motus"};
  for (const auto& c : curves)
    if (std::find(engines.begin(), engines.end(), c.engine) == engines.end()) engines.push_back(c.engine);
  fmt::print("\ntargets: the fastest method of each engine at each target error, each curve interpolated on log-log "
             "axes;\nus = microseconds of the fastest runs (the median runs'); <= : at most this (the cheapest point, or "
             "one after a blow-up, is already below the target; a ratio with one such side is a bound)\nnot reached (best E): no "
             "point of the engine's sweep gets below the target; E is the smallest error any reached (a curve\nstill falling at "
             "its finest step or tightest tolerance may get there further on)\n{:<8}", "target");
  // (The method column as wide as its longest entry: odeint's symplectic_rkn_sb3a_mclachlan is 36.)
  size_t method_width = std::string_view("not reached (best 6.7e-10)").size();
  for (const auto& c : curves) method_width = std::max(method_width, c.method.size());
  for (const auto& e : engines) fmt::print("  {:<{}}{:>18}", e, method_width, "us");
  for (size_t k = 1; k < engines.size(); ++k) fmt::print("{:>22}", "motus/" + engines[k]);
  fmt::print("\n");
  for (double target : targets) {
    fmt::print("{:<8g}", target);
    std::vector<std::optional<precision::Fastest>> best;
    for (const auto& e : engines) {
      best.push_back(precision::fastest(curves, e, target));
      fmt::print("  {:<{}}{:>18}",
                 best.back()                       ? best.back()->method
                 : precision::engine_runs(curves, e) ? precision::not_reached_text(curves, e, true)
                                                     : "cannot run this scene",
                 method_width, microseconds(best.back()));
    }
    for (size_t k = 1; k < engines.size(); ++k) fmt::print("{:>22}", precision::ratio_text(best[0], best[k], true));
    fmt::print("\n");
  }

  fmt::print("\n{}\n", compare::machine_load_sentence(load));
  if (compare::busy_machine(load)) fmt::print("warning: {}\n", compare::busy_machine_warning(load));

  precision::ReportContext context;
  context.scene = scene.name;
  context.file = path;
  context.description = scene.description;
  context.start = scene.start_time;
  context.end = end;
  context.time_unit = time_unit_of(scene);
  context.sweep = sweep;
  context.targets = targets;
  context.versions = versions;
  context.machine_load = compare::machine_load_sentence(load);
  context.busy_machine = compare::busy_machine_warning(load);
  const std::string warning = precision::write_precision_report(partial.path(), context, curves);
  if (!warning.empty()) tell("motus: {}\n", warning);
  stop_if_interrupted();
  const std::string written = partial.complete();  // (a default folder's name may have taken a number)
  fmt::print("report: {}/index.html\n", written);
  // The copy, after the report (which is whole by now): whole or not at all, and over a file that
  // appeared during the sweep only with --overwrite.
  if (!o.csv.empty()) {
    write_whole_file(o.csv, precision::precision_csv(scene.name, curves), o.overwrite);
    fmt::print("table written to {}\n", o.csv);
  }
  return 0;
}

}  // namespace motus::cli
