#include "run_command.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "motus/compare/timing.hpp"
#include "motus/simulation.hpp"
#include "progress_bar.hpp"
#include "motus/scene_file/scene_file.hpp"

namespace motus::cli {
namespace {

std::vector<double> to_std(const Vector& v) { return {v.data(), v.data() + v.size()}; }

nlohmann::json energy_json(const std::optional<Energy>& e) {
  if (!e) return nullptr;
  return {{"kinetic", e->kinetic}, {"potential", e->potential}, {"total", e->total}};
}

// Writes the trajectory CSV: a header, then one row per output time.
class TrajectoryWriter {
public:
  TrajectoryWriter(const std::string& path, const Simulation& sim, double interval)
      : path_(path), out_(path), interval_(interval) {
    if (!out_) throw InputError(path + ": cannot be written");
    out_ << "t";
    for (const auto& n : sim.state_names()) out_ << ',' << n;
    if (sim.is_mechanical()) out_ << ",kinetic,potential,total";
    if (sim.has_constraints()) out_ << ",constraint_error";
    if (!sim.is_mechanical()) {
      aux_names_ = sim.first_order_system()->auxiliary_names();
      for (const auto& n : aux_names_) out_ << ',' << n;
      aux_.resize(static_cast<Eigen::Index>(aux_names_.size()));
    }
    out_ << '\n';
    next_ = sim.time();
    row(sim);
  }
  void after_step(const Simulation& sim) {
    if (sim.time() + 1e-9 * std::max(1.0, std::abs(sim.time())) >= next_) row(sim);
  }
  // The end of the run gets a row even when it is not an output time. A write that failed
  // (a full disk) is an error naming the file, not a run that went well.
  void finish(const Simulation& sim) {
    if (sim.time() > last_) row(sim);
    out_.flush();
    if (!out_) throw std::runtime_error(path_ + ": could not be written (disk full?)");
  }

private:
  void row(const Simulation& sim) {
    out_ << fmt::format("{:.17g}", sim.time());
    for (double v : sim.state()) out_ << fmt::format(",{:.17g}", v);
    if (const auto e = sim.energy()) out_ << fmt::format(",{:.17g},{:.17g},{:.17g}", e->kinetic, e->potential, e->total);
    if (sim.has_constraints()) out_ << fmt::format(",{:.17g}", sim.constraint_error());
    if (!aux_names_.empty()) {
      sim.first_order_system()->auxiliaries(sim.time(), sim.state(), aux_);
      for (double v : aux_) out_ << fmt::format(",{:.17g}", v);
    }
    out_ << '\n';
    last_ = sim.time();
    while (next_ <= sim.time() + 1e-9 * std::max(1.0, std::abs(sim.time()))) {
      if (interval_ <= 0) {
        next_ = -INFINITY;  // every step
        break;
      }
      next_ += interval_;
    }
  }

  std::string path_;
  std::ofstream out_;
  double interval_;
  double next_ = 0;
  double last_ = -INFINITY;
  std::vector<std::string> aux_names_;
  Vector aux_;
};

// A state that overflowed is a result to show, but not a run that went well.
int report_non_finite(double by) {
  fmt::print(stderr, "motus: the run failed: the state was no longer finite by t = {:g} (the integrator is unstable "
             "at this step; try a smaller --dt or another --integrator)\n", by);
  return kExitFailure;
}

std::string vec(const Vector& v) {
  std::vector<std::string> parts;
  for (double x : v) parts.push_back(fmt::format("{:.10g}", x));
  return "(" + fmt::format("{}", fmt::join(parts, ", ")) + ")";
}

}  // namespace

CLI::App* add_run_command(CLI::App& app, RunOptions& o) {
  auto* run = app.add_subcommand("run", "Integrate one scene and report energy, momentum, steps, derivative evaluations, wall time and the final state");
  run->add_option("scene", o.scene, "Scene file, or the name of a shipped scene (see `motus list`)")->required();
  run->add_option("--integrator", o.integrator, "Integrator (default: the scene's); see `motus list`");
  run->add_option("--dt", o.dt, "Step size, s (the first step for adaptive integrators; default: the scene's)");
  auto* duration = run->add_option("--duration", o.duration, "Time to integrate, s (default: the scene's)");
  run->add_option("--steps", o.steps, "Number of steps of dt instead of a duration")->excludes(duration);
  run->add_option("--rtol", o.rtol, "Relative tolerance of rk45 and rk4-doubling (default: the scene's)");
  run->add_option("--atol", o.atol, "Absolute tolerance of rk45 and rk4-doubling (default: the scene's)");
  run->add_option("--set", o.sets, "Override a scene field, e.g. --set bodies[0].mass=2 (repeatable)")
      ->type_name("PATH=VALUE");
  run->add_option("--trajectory", o.trajectory, "Write t, state and energies per output time to this CSV file");
  run->add_flag("--overwrite", o.overwrite, "Allow --trajectory to replace an existing file");
  run->add_flag("--json", o.json, "Print one JSON object instead of the summary (see docs/cli.md)");
  run->add_option("--repeats", o.repeats,
                  "Run the scene this many times from its start; the time per step is the fastest run's CPU time, "
                  "with the median beside it (the first run is the one reported)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  add_plugin_option(run, o.plugins);
  return run;
}

int run_command(const RunOptions& o) {
  const std::string path = resolve_scene_path(o.scene);
  SceneDescription scene = load_scene(path, o.sets);
  load_plugins(o.plugins);

  const Method method = method_for(path, scene, o.integrator);
  const std::string integrator_name = method.name();
  const double dt = o.dt.value_or(scene.dt);
  if (!(dt > 0) || !std::isfinite(dt)) throw InputError("--dt: must be a finite number > 0");
  if (o.steps && *o.steps <= 0) throw InputError("--steps: must be > 0");
  const double duration = o.steps ? static_cast<double>(*o.steps) * dt : o.duration.value_or(scene.duration);
  if (!(duration > 0) || !std::isfinite(duration)) throw InputError("--duration: must be a finite number > 0");
  if (!method.adaptive()) checked_step_count(duration, dt, o.steps ? "--steps" : o.duration ? "--duration" : o.dt ? "--dt" : "dt/duration");
  const Tolerance tolerance{o.atol.value_or(scene.atol), o.rtol.value_or(scene.rtol)};
  if (!(tolerance.atol > 0) || !(tolerance.rtol > 0)) throw InputError("--atol/--rtol: must be > 0");

  Simulation sim(scene, method, plugins().parts());  // SceneError: e.g. a symplectic integrator on a first-order system
  const auto energy0 = sim.energy();
  const Vector momentum0 = sim.momentum(), angular0 = sim.angular_momentum();
  const Vector state0 = sim.state();

  std::optional<TrajectoryWriter> trajectory;
  if (!o.trajectory.empty()) {
    check_can_write(o.trajectory, o.overwrite);
    trajectory.emplace(o.trajectory, sim, scene.output_interval);
  }
  // The progress bar spans every run: the first, reported, and the others, only timed.
  const double t0 = sim.time();
  ProgressBar progress(0, o.repeats * duration, scene.name);
  const auto began = std::chrono::steady_clock::now();
  double worst_constraint_error = sim.constraint_error();
  const bool constrained = sim.has_constraints();
  double non_finite_by = NAN;  // checked every 16 steps: the first time seen not finite
  std::vector<double> round_seconds;  // CPU time of each run's advance()
  double cpu_began = compare::cpu_seconds();
  sim.advance(sim.time() + duration, dt, tolerance, [&](const Simulation& s) {
    if (trajectory) trajectory->after_step(s);
    if ((s.steps() & 15) == 0 && std::isnan(non_finite_by) && !s.state().allFinite()) non_finite_by = s.time();
    if (constrained) worst_constraint_error = std::max(worst_constraint_error, s.constraint_error());
    progress.update(s.time() - t0);
  });
  round_seconds.push_back(compare::cpu_seconds() - cpu_began);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  // The other runs: the same scene from its start with the same bookkeeping after every step
  // (the largest stick error, the finiteness check), only the trajectory is not written again.
  for (int round = 1; round < o.repeats && sim.state().allFinite(); ++round) {
    Simulation again(scene, method, plugins().parts());
    double worst = again.constraint_error();
    bool finite = true;
    cpu_began = compare::cpu_seconds();
    again.advance(again.time() + duration, dt, tolerance, [&](const Simulation& s) {
      if ((s.steps() & 15) == 0 && finite && !s.state().allFinite()) finite = false;
      if (constrained) worst = std::max(worst, s.constraint_error());
      progress.update(round * duration + s.time() - t0);
    });
    round_seconds.push_back(compare::cpu_seconds() - cpu_began);
  }
  progress.finish();
  if (trajectory) trajectory->finish(sim);
  std::vector<double> per_step;
  for (double seconds : round_seconds) per_step.push_back(sim.steps() ? 1e9 * seconds / static_cast<double>(sim.steps()) : 0);
  const compare::Timings time = compare::summarize(per_step);
  const bool adaptive = method.adaptive();
  const World* world = sim.world();
  const CollisionCounters collisions = world ? world->collision_counters() : CollisionCounters{};
  const bool finite = sim.state().allFinite();

  if (o.json) {
    nlohmann::json j;
    j["scene"] = scene.name;
    j["file"] = path;
    j["integrator"] = integrator_name;
    j["dt"] = dt;
    if (adaptive) j["tolerance"] = {{"rtol", tolerance.rtol}, {"atol", tolerance.atol}};
    j["t"] = sim.time();
    j["steps"] = sim.steps();
    j["rejected"] = sim.rejected();
    j["evaluations"] = sim.evaluations();
    j["wall_seconds"] = wall;
    j["repeats"] = static_cast<int>(round_seconds.size());
    j["ns_per_step"] = {{"min", time.min}, {"median", time.median}, {"max", time.max}, {"rounds", per_step}};
    j["energy"] = sim.is_mechanical() ? nlohmann::json{{"initial", energy_json(energy0)}, {"final", energy_json(sim.energy())}}
                                      : nlohmann::json(nullptr);
    j["momentum"] = sim.is_mechanical() ? nlohmann::json{{"initial", to_std(momentum0)}, {"final", to_std(sim.momentum())}}
                                        : nlohmann::json(nullptr);
    j["angular_momentum"] = angular0.size() ? nlohmann::json{{"initial", to_std(angular0)}, {"final", to_std(sim.angular_momentum())}}
                                            : nlohmann::json(nullptr);
    if (sim.is_mechanical()) {
      const int d = scene.mechanical->dimensions, n = sim.mechanical_system()->size();
      nlohmann::json xs = nlohmann::json::array(), vs = nlohmann::json::array();
      for (int i = 0; i < n; i += d) {
        xs.push_back(std::vector<double>(sim.state().data() + i, sim.state().data() + i + d));
        vs.push_back(std::vector<double>(sim.state().data() + n + i, sim.state().data() + n + i + d));
      }
      j["state"] = {{"x", xs}, {"v", vs}};
    } else {
      j["state"] = {{"y", to_std(sim.state())}, {"names", sim.state_names()}};
    }
    j["passes"] = world ? nlohmann::json(world->passes()) : nlohmann::json(nullptr);
    j["constraint_error"] = constrained ? nlohmann::json{{"max", worst_constraint_error}, {"final", sim.constraint_error()}}
                                        : nlohmann::json(nullptr);
    j["collisions"] = world && world->has_collisions()
                          ? nlohmann::json{{"ball", collisions.ball_collisions},
                                           {"wall", collisions.wall_collisions},
                                           {"broad_phase_queries", collisions.broad_phase_queries()},
                                           {"pair_tests", collisions.pair_tests},
                                           {"position_corrections", collisions.position_corrections}}
                          : nlohmann::json(nullptr);
    j["finite"] = finite;
    if (!o.trajectory.empty()) j["trajectory"] = o.trajectory;
    fmt::print("{}\n", j.dump(2));
    return finite ? 0 : report_non_finite(std::isnan(non_finite_by) ? sim.time() : non_finite_by);
  }

  fmt::print("scene        {}  ({})\n", scene.name, path);
  if (!scene.description.empty()) fmt::print("             {}\n", scene.description);
  fmt::print("integrator   {}{}, dt = {:g}{}\n", integrator_name, adaptive ? " (adaptive)" : "", dt,
             adaptive ? fmt::format(", rtol = {:g}, atol = {:g}", tolerance.rtol, tolerance.atol) : "");
  fmt::print("time         {:g} -> {:.10g}\n\n", scene.start_time, sim.time());
  if (sim.is_mechanical()) {
    const auto e1 = sim.energy();
    fmt::print("{:<18}{:>22}{:>22}{:>14}\n", "", "start", "end", "change");
    auto row = [](const char* name, double a, double b) {
      const double rel = a != 0 ? (b - a) / std::abs(a) : b - a;
      fmt::print("{:<18}{:>22.12g}{:>22.12g}{:>14.3e}{}\n", name, a, b, rel, a != 0 ? "" : " (abs)");
    };
    row("kinetic energy", energy0->kinetic, e1->kinetic);
    row("potential energy", energy0->potential, e1->potential);
    row("total energy", energy0->total, e1->total);
    fmt::print("{:<18}{:>30}{:>30}\n", "momentum", vec(momentum0), vec(sim.momentum()));
    if (angular0.size()) fmt::print("{:<18}{:>30}{:>30}\n", "angular momentum", vec(angular0), vec(sim.angular_momentum()));
  } else {
    const auto names = sim.state_names();
    fmt::print("{:<18}{:>22}{:>22}\n", "", "start", "end");
    for (size_t i = 0; i < names.size(); ++i)
      fmt::print("{:<18}{:>22.12g}{:>22.12g}\n", names[i], state0[static_cast<Eigen::Index>(i)],
                 sim.state()[static_cast<Eigen::Index>(i)]);
  }
  fmt::print("\nsteps        {} accepted, {} rejected\n", sim.steps(), sim.rejected());
  fmt::print("evaluations  {} derivative evaluations\n", sim.evaluations());
  fmt::print("time         {:.1f} ns per step: the fastest of {} runs (CPU time), median {:.1f}, spread {:.0f}%\n", time.min,
             time.rounds, time.median, 100 * time.spread());
  fmt::print("wall time    {:.6f} s (the first run)\n", wall);
  if (world) fmt::print("passes       {}\n", fmt::join(world->passes(), ", "));
  if (world && world->has_collisions())
    fmt::print("collisions   {} ball-ball, {} with walls; broad phase {} queries, {} pair tests; {} overlaps removed\n",
               collisions.ball_collisions, collisions.wall_collisions, collisions.broad_phase_queries(),
               collisions.pair_tests, collisions.position_corrections);
  if (constrained)
    fmt::print("constraints  largest stick-length error {:.3e} over the run, {:.3e} at the end\n", worst_constraint_error,
               sim.constraint_error());
  if (!o.trajectory.empty()) fmt::print("trajectory   {}\n", o.trajectory);
  return finite ? 0 : report_non_finite(std::isnan(non_finite_by) ? sim.time() : non_finite_by);
}

}  // namespace motus::cli
