#include "bench_precision_command.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>

#include "cli_common.hpp"
#include "motus/exact/exact_solution.hpp"
#include "motus/simulation.hpp"
#include "progress_bar.hpp"
#include "motus/scene_file/scene_file.hpp"

namespace motus::cli {
namespace {

struct Measurement {
  std::string integrator;
  double h_or_tolerance = 0;
  long steps = 0, evaluations = 0;
  double error = 0;  // max over the state of |y − y_exact| at the final time
  double t_end = 0;  // where the run ended (a fixed step may pass the requested end)
  double seconds = 0;
};

Measurement measure(const SceneDescription& scene, const Method& method, double dt, Tolerance tol, double end,
                    int repeats) {
  Measurement m;
  m.integrator = method.name();
  m.seconds = INFINITY;
  for (int r = 0; r < repeats; ++r) {
    Simulation sim(scene, method);
    const auto began = std::chrono::steady_clock::now();
    sim.advance(end, dt, tol);
    m.seconds = std::min(m.seconds, std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count());
    if (r == 0) {
      const auto exact = exact_state(scene, sim.time());
      if (!exact) throw InputError(fmt::format("{}: no reference state at t = {:g}", scene.name, sim.time()));
      m.error = (sim.state() - *exact).cwiseAbs().maxCoeff();
      if (!std::isfinite(m.error)) m.error = INFINITY;
      m.steps = sim.steps();
      m.t_end = sim.time();
      m.evaluations = sim.evaluations();
    }
  }
  return m;
}

std::string default_csv_path(const std::string& scene_name) {
  std::filesystem::create_directories("runs");
  const std::time_t now = std::time(nullptr);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
  const std::string name = safe_file_name(scene_name);  // a name is not a path
  std::string path = fmt::format("runs/precision-{}-{}.csv", name, stamp);
  for (int i = 2; std::filesystem::exists(path); ++i) path = fmt::format("runs/precision-{}-{}-{}.csv", name, stamp, i);
  return path;
}

}  // namespace

CLI::App* add_bench_precision_command(CLI::App& bench, BenchPrecisionOptions& o) {
  auto* p = bench.add_subcommand("precision", "Run time against error: sweep each integrator's step or tolerance "
                                              "and measure the final-time error against the scene's exact solution");
  p->add_option("scene", o.scene, "A scene with an exact or reference solution (spring, oscillator, kepler, pendulum, lorenz, ...)")
      ->required();
  p->add_option("--integrators", o.integrators, "Comma-separated integrators (default: every one that can run the scene)")
      ->delimiter(',');
  p->add_option("--levels", o.levels, "Steps halved (or tolerances divided by 10) this many times")->check(CLI::Range(1, 20));
  p->add_option("--repeats", o.repeats, "Runs per point; the fastest counts")->check(CLI::Range(1, 100));
  p->add_option("--duration", o.duration, "End time (default: the scene's; for reference states, the last one within it)");
  p->add_option("--set", o.sets, "Override a scene field (repeatable)")->type_name("PATH=VALUE");
  p->add_option("--csv", o.csv, "Write the table here (default: a new file under runs/)");
  p->add_flag("--overwrite", o.overwrite, "Allow --csv to replace an existing file");
  add_plugin_option(p, o.plugins);
  return p;
}

int bench_precision_command(const BenchPrecisionOptions& o) {
  const std::string path = resolve_scene_path(o.scene);
  const SceneDescription scene = load_scene(path, o.sets);
  load_plugins(o.plugins);
  if (!has_exact_solution(scene))
    throw InputError(path + ": declares no \"exact\" solution or \"reference\" states to measure error against");

  double end = scene.start_time + o.duration.value_or(scene.duration);
  if (const auto last = last_reference_time(scene)) {
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
      if (const auto id = integrator_from_name(name)) chosen.emplace_back(*id);
      else if (const auto m = plugins().integrator(name)) chosen.push_back(*m);
      else throw InputError("--integrators: unknown integrator \"" + name + "\" (known: " + known_integrators() + ")");
    }
  }

  const std::string csv_path = o.csv.empty() ? default_csv_path(scene.name) : o.csv;
  if (!o.csv.empty()) check_can_write(csv_path, o.overwrite);
  std::ofstream csv(csv_path);
  if (!csv) throw InputError(csv_path + ": cannot be written");
  csv << "scene,integrator,h,tolerance,steps,evaluations,t_end,error,seconds\n";

  fmt::print("run time against error: {} to t = {:g}; error = max |y - y_exact| over the state at the end;\n"
             "seconds = fastest of {} runs\n\n",
             scene.name, end, o.repeats);
  fmt::print("{:<20}{:>12}{:>12}{:>14}{:>14}{:>14}\n", "integrator", "h / tol", "steps", "evaluations", "error", "seconds");
  ProgressBar progress(0, static_cast<double>(chosen.size() * static_cast<size_t>(o.levels)), "bench precision", 1);
  double done = 0;
  for (const Method& method : chosen) {
    const std::string name = method.name();
    const bool adaptive = method.adaptive();
    if (method.needs_mechanical() && !scene.is_mechanical()) {
      fmt::print("{:<20}  cannot run this scene: symplectic, needs a mechanical scene (bodies)\n", name);
      done += o.levels;
      continue;
    }
    for (int level = 0; level < o.levels; ++level) {
      const double h = adaptive ? scene.dt : scene.dt / std::ldexp(1.0, level);
      const double tol = std::pow(10.0, -3 - level);
      const Measurement m = measure(scene, method, h, Tolerance{tol, tol}, end, o.repeats);
      fmt::print("{:<20}{:>12.3g}{:>12}{:>14}{:>14.3e}{:>14.3e}\n", name, adaptive ? tol : h, m.steps,
                 m.evaluations, m.error, m.seconds);
      csv << fmt::format("{},{},{:.17g},{},{},{},{:.17g},{:.6e},{:.6e}\n", scene.name, name, h,
                         adaptive ? fmt::format("{:g}", tol) : "", m.steps, m.evaluations, m.t_end, m.error, m.seconds);
      progress.update(++done);
    }
  }
  progress.finish();
  csv.flush();
  if (!csv) throw std::runtime_error(csv_path + ": could not be written (disk full?)");
  fmt::print("\ntable written to {}\n", csv_path);
  return 0;
}

}  // namespace motus::cli
