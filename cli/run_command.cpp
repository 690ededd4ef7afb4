#include "run_command.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <cmath>
#include <limits>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <optional>
#include <utility>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "integrator_choice.hpp"
#include "interrupt.hpp"
#include "locations.hpp"
#include "motus/compare/explanations.hpp"
#include "motus/compare/metrics.hpp"
#include "motus/compare/timing.hpp"
#include "motus/message_number.hpp"
#include "motus/plot/write_failure.hpp"
#include "motus/simulation.hpp"
#include "option_values.hpp"
#include "output_files.hpp"
#include "plugin_loading.hpp"
#include "progress_bar.hpp"
#include "motus/scene_file/scene_file.hpp"
#include "steps_and_times.hpp"

namespace motus::cli {

namespace {

namespace fs = std::filesystem;

std::vector<double> to_std(const Vector& v) { return {v.data(), v.data() + v.size()}; }

nlohmann::json energy_json(const std::optional<Energy>& e) {
  if (!e) return nullptr;
  return {{"kinetic", e->kinetic}, {"potential", e->potential}, {"total", e->total}};
}

// An ostream onto a C stream: the trajectory's rows onto data_output() when that is not stdout
// (a plug-in's prints were moved off standard output, and std::cout went with them).
class FileStreamBuffer : public std::streambuf {
public:
  explicit FileStreamBuffer(std::FILE* file) : file_(file) {}

protected:
  int_type overflow(int_type c) override {
    return traits_type::eq_int_type(c, traits_type::eof()) ? traits_type::not_eof(c) : std::fputc(c, file_);
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    return static_cast<std::streamsize>(std::fwrite(s, 1, static_cast<size_t>(n), file_));
  }
  int sync() override { return std::fflush(file_) == 0 ? 0 : -1; }

private:
  std::FILE* file_;
};

// Writes the trajectory CSV: a header, then one row per output time. A file is written as a
// PartialFile (in a folder of its own beside it) and moved to NAME when the run is through: a
// run that is interrupted or fails leaves no half-written CSV, and the file it would have
// replaced (--overwrite) is still there. A FIFO or a device (/dev/full) is written as it is.
class TrajectoryWriter {
public:
  // path "-": standard output.
  TrajectoryWriter(const std::string& path, const Simulation& sim, double interval, bool overwrite)
      : path_(path == "-" ? "standard output" : path), interval_(interval), overwrite_(overwrite) {
    if (path == "-" && data_output() != stdout) {
      data_buffer_.emplace(data_output());
      data_stream_.emplace(&*data_buffer_);
      out_ = &*data_stream_;
    } else if (path == "-") {
      out_ = &std::cout;
    } else {
      if (!written_in_place(path)) partial_.emplace(path);
      file_.open(partial_ ? partial_->path() : path, std::ios::binary | std::ios::trunc);
      out_ = &file_;
    }
    if (!*out_) {
      stop_if_interrupted();  // (Ctrl-C while a FIFO waited for its reader: EINTR, an interrupt, not bad input)
      throw InputError(path + ": cannot be written (" + std::strerror(errno) + ")");
    }
    *out_ << "t";
    for (const auto& n : sim.state_names()) *out_ << ',' << n;
    if (sim.is_mechanical()) *out_ << ",kinetic,potential,total";
    if (sim.has_sticks()) *out_ << ",constraint_error";
    if (!sim.is_mechanical()) {
      aux_names_ = sim.first_order_system()->auxiliary_names();
      for (const auto& n : aux_names_) *out_ << ',' << n;
      aux_.resize(static_cast<Eigen::Index>(aux_names_.size()));
    }
    *out_ << '\n';
    start_ = next_ = sim.time();
    row(sim);
  }
  void after_step(const Simulation& sim) {
    if (sim.time() + 1e-9 * std::max(1.0, std::abs(sim.time())) >= next_) row(sim);
  }
  // The end of the run gets a row even when it is not an output time. A write that failed
  // (a full disk) is an error naming the file, not a run that went well.
  void finish(const Simulation& sim) {
    if (sim.time() > last_) row(sim);
    if (*out_) errno = 0;
    out_->flush();
    check_written(*out_);
    if (partial_) {
      errno = 0;
      file_.close();
      check_written(file_);
      partial_->complete(overwrite_);
    }
  }
  ~TrajectoryWriter() { file_.close(); }  // (before the PartialFile removes it: the run did not get through)
  TrajectoryWriter(const TrajectoryWriter&) = delete;
  TrajectoryWriter& operator=(const TrajectoryWriter&) = delete;

private:
  // A write that failed stops the run at once (a reader gone, a full disk: the rest of the run
  // would be lost work), with the system's reason when it gave one.
  void check_written(const std::ostream& stream) const {
    if (!stream) throw std::runtime_error(plot::write_failure(path_));
  }
  void row(const Simulation& sim) {
    if (*out_) errno = 0;  // (so that a failed write's errno is the write's; the header's failure keeps its own)
    // The row formatted into one buffer kept from row to row, written at once (a std::string per
    // number, too long for its inline storage, was 3.7 allocations a row).
    line_.clear();
    fmt::format_to(std::back_inserter(line_), "{:.17g}", sim.time());
    for (double v : sim.state()) fmt::format_to(std::back_inserter(line_), ",{:.17g}", v);
    if (const auto e = sim.energy())
      fmt::format_to(std::back_inserter(line_), ",{:.17g},{:.17g},{:.17g}", e->kinetic, e->potential, e->total);
    if (sim.has_sticks()) fmt::format_to(std::back_inserter(line_), ",{:.17g}", sim.constraint_error());
    if (!aux_names_.empty()) {
      sim.first_order_system()->auxiliaries(sim.time(), sim.state(), aux_);
      for (double v : aux_) fmt::format_to(std::back_inserter(line_), ",{:.17g}", v);
    }
    line_.push_back('\n');
    out_->write(line_.data(), static_cast<std::streamsize>(line_.size()));
    check_written(*out_);
    last_ = sim.time();
    if (interval_ <= 0) {
      next_ = -INFINITY;  // every step
      return;
    }
    // The first output time t0 + k·interval past this row, counted (not stepped to one interval
    // at a time: an interval far below dt would take dt/interval turns, or none at all once
    // adding it to t no longer changes t). An interval below dt gives a row after every step.
    const double tolerance = 1e-9 * std::max(1.0, std::abs(sim.time()));
    const double k = std::floor((sim.time() + tolerance - start_) / interval_) + 1;
    const double next = start_ + k * interval_;
    next_ = std::isfinite(next) ? std::max(next_, next) : -INFINITY;  // (an interval of 1e-320 s: every step)
  }

  std::string path_;
  std::optional<PartialFile> partial_;  // the file written until the move (none: standard output, a FIFO, a device)
  std::ofstream file_;
  std::optional<FileStreamBuffer> data_buffer_;  // standard output kept apart from a plug-in's prints
  std::optional<std::ostream> data_stream_;
  std::ostream* out_ = nullptr;
  fmt::memory_buffer line_;  // (row's)
  double interval_;
  bool overwrite_;
  double start_ = 0, next_ = 0;  // the first row's time, and the next output time
  double last_ = -INFINITY;
  std::vector<std::string> aux_names_;
  Vector aux_;
};

// A state that overflowed is a result to show, but not a run that went well.
// A state still finite whose energy is not (an oscillator at 1e193 m: its ½ k x² overflows) has
// blown up as surely: it was reported as a run that went well, "total energy 0.5 inf".
int report_non_finite(double by, const Simulation& sim, const Method& method) {
  const bool state = !sim.state().allFinite();
  tell("motus: the run failed: the {} was no longer finite by t = {:g} ({}{})\n", state ? "state" : "energy", by,
       state ? "" : "its largest number had reached " + message_number(sim.state().cwiseAbs().maxCoeff(), 2) + "; ",
       non_finite_suspect(sim, method));
  return kExitFailure;
}

// A NaN without its sign: printf and fmt write a negative one as "-nan", which reads as a
// number with a sign; every NaN of a blown-up run is "nan".
double unsigned_nan(double x) { return std::isnan(x) ? std::numeric_limits<double>::quiet_NaN() : x; }

// A vector as the summary prints it: (1.5, -2, nan).
std::string vector_text(ConstVectorRef v) {
  std::vector<std::string> parts;
  for (Eigen::Index i = 0; i < v.size(); ++i) parts.push_back(fmt::format("{:.10g}", unsigned_nan(v[i])));
  return fmt::format("({})", fmt::join(parts, ", "));
}

// A time as a person reads it: "3.2 µs", "5.28 ms", "1.6 s".
// Three significant digits in every unit, in the largest unit the time still reaches once
// rounded to them: 999.7 ns reads "1 µs", never "1e+03 ns"; 927 ns reads "927 ns", never
// "927.0 ns" (a clock that counts whole nanoseconds made a tenth of one look measured).
std::string duration_text(double seconds) {
  static constexpr std::pair<double, const char*> kUnits[] = {{1e-9, "ns"}, {1e-6, "µs"}, {1e-3, "ms"}};
  for (const auto& [scale, unit] : kUnits) {
    const std::string digits = fmt::format("{:.3g}", seconds / scale);
    if (std::abs(std::strtod(digits.c_str(), nullptr)) < 1000) return digits + " " + unit;
  }
  return fmt::format("{:.3g} s", seconds);
}

// World2 runs in years; everything else in seconds.
std::string time_unit(const SceneDescription& scene) {
  return " (" + time_unit_of(scene) + ")";
}

// A run this short is printed step by step (the course's spring: six rows).
constexpr size_t kTableRows = 12;
constexpr int kBodiesShown = 4;
// A state of at most this many numbers is looked at for non-finite ones after every step.
constexpr Eigen::Index kLookEveryStepUpTo = 64;

// One row per recorded step: t, then the columns (x, v, a for a body; the variables of a system).
void print_table(std::FILE* out, const std::vector<std::vector<double>>& rows, const std::vector<std::string>& names) {
  fmt::print(out, "{:>10}", "t");
  for (const auto& n : names) fmt::print(out, "{:>14}", n);
  fmt::print(out, "\n");
  // A column is 14 wide and its number at most 13, so that a space always parts two (a negative
  // number in exponent form, -1.2345678e-05, takes all 14 at 8 digits: it gets 7).
  auto cell = [](double value) {
    std::string text = fmt::format("{:.8g}", value);
    for (int digits = 7; text.size() > 13 && digits >= 1; --digits) text = fmt::format("{:.{}g}", value, digits);
    return fmt::format("{:>14}", text);
  };
  for (const auto& row : rows) {
    // (t to 9 figures: a start at 1 with dt = 1e-7 printed six rows of "1")
    for (size_t k = 0; k < row.size(); ++k) fmt::print(out, "{}", k == 0 ? fmt::format("{:>10.9g}", row[k]) : cell(row[k]));
    fmt::print(out, "\n");
  }
}

}  // namespace

CLI::App* add_run_command(CLI::App& app, RunOptions& o) {
  auto* run = app.add_subcommand("run", "Integrate one scene and report energy, momentum, steps, derivative evaluations, wall time and the final state");
  run->add_option("scene", o.scene, "Scene file, or the name of a shipped scene (see `motus list`)")->required();
  run->add_option("--integrator", o.integrator, "Integrator (default: the scene's); see `motus list`");
  run->add_option("--dt", o.dt, "Step size, s (World2: years; the first step for adaptive integrators; default: the scene's)")
      ->transform(a_number());
  auto* duration = run->add_option("--duration", o.duration, "Time to integrate, s (World2: years; default: the scene's)")
                       ->transform(a_number());
  run->add_option("--steps", o.steps, "Number of steps of dt instead of a duration (1 to 10^15)")
      ->transform(whole_number_in(1, 1'000'000'000'000'000))  // (checked as written: a number past a long is not taken for the largest)
      ->excludes(duration);
  run->add_option("--rtol", o.rtol, "Relative tolerance of rk45, dop853 and rk4-doubling (default: the scene's)")->transform(a_number());
  run->add_option("--atol", o.atol, "Absolute tolerance of rk45, dop853 and rk4-doubling (default: the scene's)")->transform(a_number());
  run->add_option("--set", o.sets, "Override a scene field, e.g. --set bodies[0].mass=2 (repeatable)")
      ->type_name("PATH=VALUE");
  CLI::Option* trajectory = run->add_option("--trajectory", o.trajectory, "Write t, state and energies per output time to this CSV file (- or /dev/stdout: standard output)")
      ->check(non_empty_path())
      ->transform([](std::string path) {  // (/dev/stdout is -: not a link to write a file through)
        return path == "/dev/stdout" || path == "/dev/fd/1" || path == "/proc/self/fd/1" ? std::string("-") : path;
      });
  // (Without a file to replace it would be taken and do nothing.)
  run->add_flag("--overwrite", o.overwrite, "Allow --trajectory to replace an existing file")->needs(trajectory);
  run->add_flag("--json", o.json, "Print one JSON object instead of the summary (see docs/cli.md)");
  run->add_option("--repeats", o.repeats,
                  "Run the scene this many times from its start; the time per step is the fastest run's CPU time, "
                  "with the median beside it (the first run is the one reported; default: 5, or as many as fit in "
                  "about 1 s when one run takes longer)")
      ->transform(whole_number_in(1, 100));
  add_plugin_option(run, o.plugins);
  return run;
}

int run_command(const RunOptions& o) {
  const std::string path = resolve_scene_path(o.scene);
  SceneDescription scene = load_scene(path, o.sets);
  load_plugins(o.plugins, o.json || o.trajectory == "-");

  const Method method = method_for(path, scene, o.integrator);
  const std::string integrator_name = method.name();
  const double dt = o.dt.value_or(scene.dt);
  if (!(dt > 0) || !std::isfinite(dt)) throw InputError("--dt: must be a finite number > 0");
  const double duration = o.steps ? static_cast<double>(*o.steps) * dt : o.duration.value_or(scene.duration);
  if (o.steps && !std::isfinite(duration))
    throw InputError(fmt::format("--steps: {} steps of {:g} s is more time than a double holds", *o.steps, dt));
  if (!(duration > 0) || !std::isfinite(duration)) throw InputError("--duration: must be a finite number > 0");
  const std::string what = o.steps ? "--steps" : o.duration ? "--duration" : o.dt ? "--dt" : path + ": dt/duration";
  if (!method.adaptive()) checked_step_count(duration, dt, what);
  check_time_resolution(scene.start_time, duration, dt, path + ": start_time", what);
  check_position_resolution(scene, dt, path, o.dt ? "--dt" : path + ": dt");
  const Tolerance tolerance{o.atol.value_or(scene.atol), o.rtol.value_or(scene.rtol)};
  if (!(tolerance.atol > 0) || !(tolerance.rtol > 0) || !std::isfinite(tolerance.atol) || !std::isfinite(tolerance.rtol))
    throw InputError("--atol/--rtol: must be finite and > 0");
  // (A fixed step would take them and change nothing: a user comparing tolerances would compare one run.)
  if ((o.atol || o.rtol) && !method.adaptive())
    throw InputError(std::string(o.rtol ? "--rtol" : "--atol") + ": " + integrator_name +
                     " takes fixed steps and no tolerance (rk45, dop853 and rk4-doubling take one)");

  Simulation sim(scene, method, plugins().parts());  // SceneError: e.g. a symplectic integrator on a first-order system
  // A plug-in of which this run uses nothing (cloth's projection on spring) says so, on standard
  // error (--json's object is standard output's): its run is motus's own code.
  for (const auto& note : unused_plugin_notes(scene.name, method, sim.world())) tell("{}\n", note);
  // A scene that starts overlapping (two balls, or a body and a wall) is moved apart before the
  // first step, as documented; said on standard error, so that a typo in a position does not make a
  // plausible run without a word.
  if (const std::string start = compare::initial_overlap_note(scene, false); !start.empty())
    tell("note: {}: {}\n", path, start);
  const auto energy0 = sim.energy();
  const Vector momentum0 = sim.momentum(), angular0 = sim.angular_momentum();
  const Vector state0 = sim.state();

  std::optional<TrajectoryWriter> trajectory;
  if (o.trajectory == "-" && o.json)
    throw InputError("--trajectory -: standard output is the CSV's; --json wants it too (write the CSV to a file)");
  if (!o.trajectory.empty()) {
    if (o.trajectory != "-") {
      // Never the run's own input, however spelt (--overwrite is for an earlier CSV): a scene named
      // again as its --trajectory was replaced by the CSV (an audit).
      std::error_code same;
      if (std::filesystem::equivalent(o.trajectory, path, same))
        throw InputError("--trajectory: " + o.trajectory + " is the scene this run reads; write the CSV elsewhere");
      for (const auto& plugin : o.plugins)
        if (std::filesystem::equivalent(o.trajectory, plugin, same))
          throw InputError("--trajectory: " + o.trajectory + " is the plug-in this run loads; write the CSV elsewhere");
      check_can_write(o.trajectory, o.overwrite);
    }
    trajectory.emplace(o.trajectory, sim, scene.output_interval, o.overwrite);
    // A trajectory that will fill a disk is said before it starts (10,000 balls for 3000 s at
    // dt = 1/60 make 140 GB): rows × columns × about 20 bytes a number.
    if (!method.adaptive()) {
      const double steps = static_cast<double>(fixed_step_count(duration, dt));
      const double rows = 1 + (scene.output_interval > 0 ? std::min(steps, duration / scene.output_interval) : steps);
      const double gigabytes = rows * static_cast<double>(sim.state().size() + 4) * 20 / 1e9;
      if (gigabytes > 2)
        tell(
                   "motus: note: the trajectory will be about {:.0f} GB ({:.3g} rows); --set output_interval=S writes "
                   "a row every S s only\n",
                   gigabytes, rows);
    }
  }
  // A short run is shown step by step: the time, the state and (for bodies) the acceleration.
  std::vector<std::vector<double>> table;
  std::vector<std::string> table_names;
  const bool small_state = sim.is_mechanical() ? sim.mechanical_system()->particles() <= 2 : sim.state().size() <= 6;
  bool tabulate = small_state && (method.adaptive() || fixed_step_count(duration, dt) < static_cast<long>(kTableRows));
  Vector acceleration(sim.is_mechanical() ? sim.mechanical_system()->size() : 0);
  auto tabulate_row = [&](const Simulation& s) {
    std::vector<double> row = {s.time()};
    if (s.is_mechanical()) {
      const Eigen::Index n = s.mechanical_system()->size();
      MechanicalSystem measuring = *s.mechanical_system();  // (a copy: it counts evaluations)
      measuring.acceleration(s.time(), s.state().head(n), s.state().tail(n), acceleration);
      for (Eigen::Index i = 0; i < n; ++i) row.insert(row.end(), {s.state()[i], s.state()[n + i], acceleration[i]});
    } else {
      row.insert(row.end(), s.state().data(), s.state().data() + s.state().size());
    }
    table.push_back(std::move(row));
    if (table.size() > kTableRows) tabulate = false;
  };
  if (tabulate) {
    if (sim.is_mechanical()) {
      static const char* axes[] = {"x", "y", "z"};
      const int d = sim.mechanical_system()->dimensions();
      for (int b = 0; b < sim.mechanical_system()->particles(); ++b)
        for (int k = 0; k < d; ++k) {
          const bool one = sim.mechanical_system()->particles() == 1;
          const std::string suffix = std::string(axes[k]) + (one ? "" : std::to_string(b));
          if (one && d == 1) table_names.insert(table_names.end(), {"x", "v", "a"});  // as the course writes it
          else for (const char* q : {"", "v", "a"}) table_names.push_back(std::string(q) + suffix);
        }
    } else {
      table_names = sim.state_names();
    }
    tabulate_row(sim);
  }
  // The progress bar: the first run, reported, then a phase for the others, only timed.
  const double t0 = sim.time();
  ProgressBar progress(0, duration, scene.name);
  const auto began = std::chrono::steady_clock::now();
  // The largest of a run's errors, as `motus compare`'s column takes it (compare::worse): an error
  // that stopped being a number is the worst of all, inf (std::max would drop it, and a stick or pin
  // error would read as the last finite one; kept as NaN, run said "nan" where compare said inf).
  using compare::worse;
  double worst_constraint_error = sim.constraint_error();
  const bool constrained = sim.has_sticks();
  // Pins: motus's projection places them exactly, a plug-in's may not (its bodies then fall away
  // while the sticks between them stay true). After every step, not at the start: a scene may
  // start a body away from its pin, which the first projection puts it on.
  double worst_pin_error = 0;
  const bool pinned = sim.has_pins();
  // The first time the state was seen not finite: looked at after every step when it is small (a
  // student's spring: "by t = 5" for a NaN from t = 1 sent them to the wrong step), every 16 steps
  // when a look would cost about what the step does.
  double non_finite_by = NAN;
  const long look_every = sim.state().size() <= kLookEveryStepUpTo ? 1 : 16;
  std::vector<double> round_seconds;  // CPU time of each timed run's advance()
  // A first run that writes the trajectory or the step table is not timed: writing a CSV row (or
  // copying the system for a row's accelerations) after every step took 30 times the step itself
  // (the oscillator: 976 against 31 ns per step). The timed runs then all come after it.
  const bool first_writes = trajectory || tabulate;
  double cpu_began = compare::cpu_seconds();
  sim.advance(sim.time() + duration, dt, tolerance, [&](const Simulation& s) {
    if (trajectory) trajectory->after_step(s);
    if (tabulate) tabulate_row(s);
    if (s.steps() % look_every == 0 && std::isnan(non_finite_by) && !s.state().allFinite()) non_finite_by = s.time();
    if (constrained) worst_constraint_error = worse(worst_constraint_error, s.constraint_error());
    if (pinned) worst_pin_error = worse(worst_pin_error, s.pin_error());
    progress.update(s.time() - t0);
  });
  const double first_seconds = compare::cpu_seconds() - cpu_began;
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  if (!first_writes) round_seconds.push_back(first_seconds);
  // The other runs: the same scene from its start with the same bookkeeping after every step
  // (the largest stick error, the finiteness check), only nothing is written.
  const int rounds = o.repeats > 0 ? o.repeats : compare::auto_rounds(first_seconds, compare::kRunBudget);
  const int runs = rounds + (first_writes ? 1 : 0);
  if (runs > 1) progress.phase("timing", duration, runs * duration);
  QuietStandardOutput quiet;  // a plug-in's prints come once, with the run reported
  if (!plugins().empty()) quiet.begin();
  for (int round = 1; round < runs && sim.state().allFinite(); ++round) {
    Simulation again(scene, method, plugins().parts());
    double worst = again.constraint_error(), worst_pin = 0;
    bool finite = true;
    const auto again_began = std::chrono::steady_clock::now();
    cpu_began = compare::cpu_seconds();
    again.advance(again.time() + duration, dt, tolerance, [&](const Simulation& s) {
      if (s.steps() % look_every == 0 && finite && !s.state().allFinite()) finite = false;
      if (constrained) worst = worse(worst, s.constraint_error());
      if (pinned) worst_pin = worse(worst_pin, s.pin_error());
      progress.update(round * duration + s.time() - t0);
    });
    round_seconds.push_back(compare::cpu_seconds() - cpu_began);
    if (round_seconds.size() == 1)  // (the wall time reported is the first timed run's)
      wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - again_began).count();
  }
  quiet.end();
  // A run that was no longer finite is not run again: its one run is all there is to time.
  if (round_seconds.empty()) round_seconds.push_back(first_seconds);
  progress.finish();
  if (trajectory) trajectory->finish(sim);
  if (!tabulate) table.clear();
  std::vector<double> per_step;
  for (double seconds : round_seconds) per_step.push_back(sim.steps() ? 1e9 * seconds / static_cast<double>(sim.steps()) : 0);
  const compare::Timings time = compare::summarize(per_step);
  const bool adaptive = method.adaptive();
  const World* world = sim.world();
  const CollisionCounters collisions = world ? world->collision_counters() : CollisionCounters{};
  const std::optional<Energy> end_energy = sim.energy();
  const bool finite = sim.state().allFinite() && (!end_energy || std::isfinite(end_energy->total));

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
    j["pin_error"] = pinned ? nlohmann::json{{"max", worst_pin_error}, {"final", sim.pin_error()}} : nlohmann::json(nullptr);
    j["collisions"] = world && world->has_collisions()
                          ? nlohmann::json{{"ball", collisions.ball_collisions},
                                           {"wall", collisions.wall_collisions},
                                           {"broad_phase_queries", collisions.broad_phase_queries()},
                                           {"pair_tests", collisions.pair_tests},
                                           {"position_corrections", collisions.position_corrections}}
                          : nlohmann::json(nullptr);
    j["finite"] = finite;
    if (!o.trajectory.empty()) j["trajectory"] = o.trajectory;
    fmt::print(data_output(), "{}\n", j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace));  // (a path not in UTF-8)
    return finite ? 0 : report_non_finite(std::isnan(non_finite_by) ? sim.time() : non_finite_by, sim, method);
  }

  // With --trajectory - the CSV is standard output, and the summary goes to standard error.
  std::FILE* out = o.trajectory == "-" ? stderr : stdout;
  // (On one line each, shortened in the middle past 600 characters: a scene file's 50 MB
  // description, or a name with a newline in it, is not printed as it is.)
  fmt::print(out, "scene        {}  ({})\n", one_line(scene.name, 600), path);
  if (!scene.description.empty()) fmt::print(out, "             {}\n", one_line(scene.description, 600));
  if (!o.sets.empty())
    fmt::print(out, "             ({}this run changed {})\n",
               scene.description.empty() ? "" : "the description is the file's; ", fmt::join(o.sets, ", "));
  fmt::print(out, "integrator   {}{}, dt = {:g}{}\n", integrator_name, adaptive ? " (adaptive)" : "", dt,
             adaptive ? fmt::format(", rtol = {:g}, atol = {:g}", tolerance.rtol, tolerance.atol) : "");
  fmt::print(out, "time         {:.10g} -> {:.10g}{}\n\n", scene.start_time, sim.time(), time_unit(scene));
  if (table.size() > 1) {  // a short run: every step, as the course's tables have it
    print_table(out, table, table_names);
    fmt::print(out, "\n");
  }
  if (sim.is_mechanical()) {
    const auto e1 = sim.energy();
    fmt::print(out, "{:<18}{:>22}{:>22}{:>14}\n", "", "start", "end", "change");
    auto row = [&](const char* name, double a, double b) {
      const double rel = a != 0 ? (b - a) / std::abs(a) : b - a;
      fmt::print(out, "{:<18}{:>22.12g}{:>22.12g}{:>14.3e}{}\n", name, unsigned_nan(a), unsigned_nan(b), unsigned_nan(rel),
                 a != 0 ? "" : " (abs)");
    };
    row("kinetic energy", energy0->kinetic, e1->kinetic);
    row("potential energy", energy0->potential, e1->potential);
    row("total energy", energy0->total, e1->total);
    fmt::print(out, "{:<18}{}  ->  {}\n", "momentum", vector_text(momentum0), vector_text(sim.momentum()));
    if (angular0.size()) fmt::print(out, "{:<18}{}  ->  {}\n", "angular momentum", vector_text(angular0), vector_text(sim.angular_momentum()));
    // The final state of a few bodies (--json and --trajectory have all of them).
    const int d = scene.mechanical->dimensions, n = sim.mechanical_system()->size();
    const int bodies = n / d;
    if (bodies <= kBodiesShown) {
      fmt::print(out, "\n");
      for (int b = 0; b < bodies; ++b)
        fmt::print(out, "{:<18}x = {}   v = {}\n", bodies == 1 ? "final state" : fmt::format("body {}, end", b),
                   vector_text(sim.state().segment(b * d, d)), vector_text(sim.state().segment(n + b * d, d)));
    }
  } else {
    const auto names = sim.state_names();
    fmt::print(out, "{:<18}{:>22}{:>22}\n", "", "start", "end");
    for (size_t i = 0; i < names.size(); ++i)
      fmt::print(out, "{:<18}{:>22.12g}{:>22.12g}\n", names[i], unsigned_nan(state0[static_cast<Eigen::Index>(i)]),
                 unsigned_nan(sim.state()[static_cast<Eigen::Index>(i)]));
  }
  fmt::print(out, "\nsteps        {} accepted, {} rejected\n", sim.steps(), sim.rejected());
  fmt::print(out, "evaluations  {} derivative evaluations\n", sim.evaluations());
  if (time.rounds == 1)
    fmt::print(out, "time         {} per step: one run (CPU time)\n", duration_text(1e-9 * time.min));
  else
    fmt::print(out, "time         {} per step: the fastest of {} runs (CPU time), median {}, spread {:.0f}%\n",
               duration_text(1e-9 * time.min), time.rounds, duration_text(1e-9 * time.median), 100 * time.spread());
  fmt::print(out, "wall time    {} ({} per step, the first timed run)\n", duration_text(wall),
             duration_text(sim.steps() ? wall / static_cast<double>(sim.steps()) : 0.0));
  if (world) fmt::print(out, "passes       {}\n", fmt::join(world->passes(), ", "));
  // Verlet's contacts are positions moved apart, with no velocity to reverse: a scene whose
  // restitution asks for a bounce loses the approach speed at every contact (head_on, e = 1, lost
  // 75 % of its energy with no word but the energy line's, while its description promised a bounce).
  if (world && world->ignores_restitution())
    fmt::print(out, "contacts     projected apart (verlet): restitution is not used, so each contact loses the speed its "
                    "bodies met with (symplectic-euler's impulses use it)\n");
  if (world && world->has_collisions())
    fmt::print(out, "collisions   {} ball-ball, {} with walls; broad phase {} queries, {} pair tests; {} overlaps removed\n",
               collisions.ball_collisions, collisions.wall_collisions, collisions.broad_phase_queries(),
               collisions.pair_tests, collisions.position_corrections);
  if (constrained)
    fmt::print(out, "constraints  largest stick-length error {:.3e} over the run, {:.3e} at the end\n", worst_constraint_error,
               unsigned_nan(sim.constraint_error()));
  if (pinned && worst_pin_error != 0)  // (never after motus's own projection: no line to read past)
    fmt::print(out, "pins         a pinned body was up to {:.3e} m off its pin over the run, {:.3e} m at the end\n",
               worst_pin_error, unsigned_nan(sim.pin_error()));
  if (!o.trajectory.empty()) fmt::print(out, "trajectory   {}\n", o.trajectory == "-" ? "standard output" : o.trajectory);
  return finite ? 0 : report_non_finite(std::isnan(non_finite_by) ? sim.time() : non_finite_by, sim, method);
}

}  // namespace motus::cli
