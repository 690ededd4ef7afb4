#include "motus/compare/comparison.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "motus/compare/backends/motus_backend.hpp"
#include "motus/simulation.hpp"
#include "motus/systems/mechanical_system.hpp"

namespace motus::compare {

double in_energy_unit(double change, double divisor) { return divisor != 0 ? change / divisor : change; }

double length_of_change(const std::vector<double>& from, const std::vector<double>& to) {
  Eigen::VectorXd change(static_cast<Eigen::Index>(to.size()));
  for (size_t k = 0; k < to.size(); ++k) change[static_cast<Eigen::Index>(k)] = to[k] - (k < from.size() ? from[k] : 0);
  return change.stableNorm();  // (as metrics.cpp's distances: scaled, so that no square overflows)
}

Timings EngineRun::microseconds_per_step() const {
  std::vector<double> per_step;
  for (double seconds : round_seconds) per_step.push_back(steps ? 1e6 * seconds / static_cast<double>(steps) : 0);
  return summarize(per_step);
}

namespace {

// How often the metrics run reports its progress (where Ctrl-C is noticed): every this many steps.
constexpr long kProgressEvery = 64;
// About how long a block of a long timed run lasts between two reports of its progress.
constexpr double kTimedBlockSeconds = 0.1;
// The run whose start decides the columns' units: motus's, else the first that ran.
const EngineRun* unit_reference(const std::vector<EngineRun>& runs) {
  const EngineRun* reference = nullptr;
  for (const auto& r : runs)
    if (r.supported && !r.rows.empty() && (!reference || (r.engine == "motus" && reference->engine != "motus")))
      reference = &r;
  return reference;
}
}  // namespace

bool energy_in_joules(const std::vector<EngineRun>& runs) {
  const EngineRun* reference = unit_reference(runs);
  return reference && reference->rows.front().total == 0;
}

bool momentum_in_kg_m_s(const std::vector<EngineRun>& runs) {
  const EngineRun* reference = unit_reference(runs);
  if (!reference || reference->scale_of_momentum > 0) return false;
  return std::all_of(reference->rows.front().momentum.begin(), reference->rows.front().momentum.end(),
                     [](double p) { return p == 0; });
}

double energy_divisor(const std::vector<EngineRun>& runs, const EngineRun& r) {
  const EngineRun* reference = unit_reference(runs);
  if (!reference || reference->rows.front().total == 0) return 0;  // in joules
  const double own = r.rows.empty() ? 0 : r.rows.front().total;
  return std::abs(own != 0 ? own : reference->rows.front().total);
}

double EngineRun::energy_drift(double divisor) const {
  return in_energy_unit(rows.back().total - rows.front().total, divisor);
}

double EngineRun::max_energy_error(double divisor) const {
  double worst = 0;
  for (const auto& r : rows) worst = worse(worst, std::abs(in_energy_unit(r.total - rows.front().total, divisor)));
  return worst;
}

double EngineRun::momentum_scale() const {
  const double scale = std::max(length_of_change({}, rows.front().momentum), scale_of_momentum);
  return scale > 0 ? scale : 1;
}

double EngineRun::momentum_drift() const {
  return length_of_change(rows.front().momentum, rows.back().momentum) / momentum_scale();
}

double EngineRun::max_penetration() const {
  double worst = penetration_every_step;
  for (const auto& r : rows) worst = worse(worst, r.penetration);
  return worst;
}

double EngineRun::max_constraint_error() const {
  // From the first step on: the start is the scene's (a stick written 1 m long between bodies
  // 0.943 m apart charged every engine alike with 5.7 %, found by an audit).
  double worst = stick_error_every_step;
  for (size_t i = 1; i < rows.size(); ++i) worst = worse(worst, rows[i].constraint_error);
  return worst;
}

double EngineRun::start_constraint_error() const { return rows.empty() ? 0 : rows.front().constraint_error; }

double EngineRun::not_finite_from() const {
  for (const auto& r : rows)
    if (!std::isfinite(r.total)) return r.t;
  return NAN;
}

double EngineRun::max_from_motus() const {
  double worst = 0;
  for (const auto& r : rows) worst = worse(worst, r.from_motus);
  return worst;
}

double EngineRun::max_from_exact() const {
  double worst = -1;
  for (const auto& r : rows) worst = worse(worst, r.from_exact);
  return worst;
}

std::vector<EngineRun> run_comparison(const SceneDescription& scene, const ComparisonOptions& options,
                                      const std::function<void(double)>& progress) {
  const Metrics metrics(scene);
  const bool sticks = !scene.mechanical->sticks.empty();
  const bool contacts = metrics.has_contacts();
  const long steps = fixed_step_count(options.duration, options.dt);
  // The samples after the start: `samples` of them (every step when the run has fewer), at the
  // steps nearest to k·steps/samples, k = 1 … samples — the last at the end.
  const long samples = std::min(std::max(1L, options.samples), steps);
  auto sample_step = [&](long k) {
    return k >= samples ? steps : std::llround(static_cast<double>(k) * static_cast<double>(steps) / static_cast<double>(samples));
  };
  double scale = 0;
  for (const auto& b : scene.mechanical->bodies) {
    double speed2 = 0;
    for (double c : b.velocity) speed2 += c * c;
    scale += b.mass * std::sqrt(speed2);
  }

  // motus runs first when asked for: its snapshots are the others' reference trajectory.
  std::vector<std::string> order = options.engines;
  std::stable_partition(order.begin(), order.end(), [](const std::string& e) { return e == "motus"; });
  std::vector<Snapshot> reference;
  std::vector<EngineRun> runs;
  // Until the metrics runs say how long a round takes, the progress counts on kMostRounds (auto).
  int repeats = options.repeats > 0 ? options.repeats : kMostRounds;
  // (in double: no overflow)
  double total_steps = static_cast<double>(steps) * static_cast<double>(order.size()) * (1.0 + repeats);
  double done = 0;
  auto make = [&](const std::string& name) -> std::unique_ptr<Backend> {
    const bool plugin = options.plugin && name == options.plugin->name;
    return plugin ? std::make_unique<MotusBackend>(name, options.plugin->version, options.plugin->parts)
                  : make_backend(name);
  };
  auto method_of = [&](const std::string& name) {
    const bool plugin = options.plugin && name == options.plugin->name;
    return plugin ? options.plugin->method.value_or(options.method) : options.method;
  };

  // The metrics run of each engine (how long it took decides only how often a timing round
  // may stop its clock to report progress).
  std::vector<double> metrics_seconds;
  for (const auto& name : order) {
    const double metrics_began = cpu_seconds();
    EngineRun run;
    run.engine = name;
    run.scale_of_momentum = scale;
    std::unique_ptr<Backend> backend = make(name);
    run.version = backend->version();
    try {
      backend->build(scene, method_of(name), options.dt);
    } catch (const Unsupported& e) {
      run.supported = false;
      for (const auto& element : e.elements()) run.unsupported.push_back("not supported by " + name + ": " + element);
      runs.push_back(run);
      metrics_seconds.push_back(0);
      done += static_cast<double>(steps);
      continue;
    }
    run.settings = backend->settings();
    Snapshot s;
    backend->read(s);
    const bool is_reference = name == "motus";
    auto sample = [&](size_t index) {
      const Snapshot* motus = !is_reference && index < reference.size() ? &reference[index] : nullptr;
      run.rows.push_back(metrics.measure(s, is_reference ? &s : motus));
      if (is_reference) reference.push_back(s);
    };
    sample(0);
    const MechanicalSystem energy_of = [&] {
      std::vector<double> masses;
      for (const auto& b : scene.mechanical->bodies) masses.push_back(b.mass);
      return MechanicalSystem(scene.mechanical->dimensions, masses, scene.mechanical->forces);
    }();
    auto keep_frame = [&] {  // the state and its energy, for a picture
      run.frames.push_back(s);
      const Eigen::Map<const Vector> x(s.x.data(), static_cast<Eigen::Index>(s.x.size()));
      const Eigen::Map<const Vector> v(s.v.data(), static_cast<Eigen::Index>(s.v.size()));
      run.frame_energies.push_back(energy_of.kinetic_energy(v) + energy_of.potential_energy(x));
    };
    if (options.frame_every > 0) keep_frame();
    size_t index = 1;
    long next_sample = sample_step(1);
    for (long i = 0; i < steps;) {
      // Step to the next sample (or frame).
      long batch = next_sample - i;
      if (options.frame_every > 0) batch = std::min(batch, options.frame_every - i % options.frame_every);
      // The progress, where a Ctrl-C is noticed, every kProgressEvery steps too, not only at a
      // sample: samples came steps/200 apart (3e5 steps of ball_gas in a long run, tens of
      // seconds), and a Ctrl-C waited for the 30 s backstop. (A call per 64 steps costs nothing
      // next to them: the bar reads the clock only now and then.)
      for (long b = 0; b < batch;) {
        const long chunk = std::min(kProgressEvery, batch - b);
        if (sticks || contacts) {  // (the stick error and the overlap every step: this run is not timed)
          for (long c = 0; c < chunk; ++c) {
            backend->step();
            backend->read(s);
            if (sticks) run.stick_error_every_step = worse(run.stick_error_every_step, metrics.stick_error(s));
            if (contacts) run.penetration_every_step = worse(run.penetration_every_step, metrics.deepest_penetration(s.x));
          }
        } else {
          for (long c = 0; c < chunk; ++c) backend->step();
        }
        b += chunk;
        if (progress && b < batch) progress((done + static_cast<double>(i + b)) / total_steps);
      }
      i += batch;
      backend->read(s);
      if (i == next_sample) {
        sample(index++);
        next_sample = sample_step(static_cast<long>(index));
        if (progress) progress((done + static_cast<double>(i)) / total_steps);
      }
      // (and the last state always: the report shows where each engine ended)
      if (options.frame_every > 0 && (i % options.frame_every == 0 || i == steps)) keep_frame();
    }
    run.steps = steps;
    run.last = s;
    run.notes = backend->notes();  // after the run: limits that bit during it
    done += static_cast<double>(steps);
    runs.push_back(std::move(run));
    metrics_seconds.push_back(cpu_seconds() - metrics_began);
  }

  // The timing rounds: a fresh world each, only its steps timed.
  std::vector<size_t> timed;
  for (size_t e = 0; e < runs.size(); ++e)
    if (runs[e].supported) timed.push_back(e);
  total_steps = done + static_cast<double>(steps) * static_cast<double>(timed.size()) * repeats;
  struct TimingRounds {
    const std::function<void(bool)>& tell;
    explicit TimingRounds(const std::function<void(bool)>& f) : tell(f) {
      if (tell) tell(true);
    }
    ~TimingRounds() {
      if (tell) tell(false);
    }
  } timing_rounds(options.timing_rounds);
  for (int round = 0; round < repeats; ++round) {
    for (size_t turn = 0; turn < timed.size(); ++turn) {
      const size_t e = timed[taking_turns(timed.size(), static_cast<size_t>(round), turn)];
      EngineRun& run = runs[e];
      std::unique_ptr<Backend> backend = make(run.engine);
      backend->build(scene, method_of(run.engine), options.dt);
      backend->watch_for_notes(false);  // (the metrics run took the notes)
      // One block of steps; a long run (a quarter of a second or more) in twenty, to show
      // progress, where reading the clock twenty times costs nothing next to the blocks; and a
      // longer one in blocks of about kTimedBlockSeconds (as the metrics run took: the timed one is
      // faster), so that a Ctrl-C, noticed between blocks, is not kept waiting for a twentieth of
      // a run of minutes.
      const long blocks =
          !progress || metrics_seconds[e] <= 0.25
              ? 1
              : static_cast<long>(std::min(static_cast<double>(steps),
                                           std::max(20.0, std::ceil(metrics_seconds[e] / kTimedBlockSeconds))));
      const long block_steps = std::max(1L, (steps + blocks - 1) / blocks);
      double seconds = 0;
      for (long i = 0; i < steps;) {
        const long block = std::min(block_steps, steps - i);
        const double began = cpu_seconds();
        for (long b = 0; b < block; ++b) backend->step();
        seconds += cpu_seconds() - began;
        i += block;
        if (progress) progress((done + static_cast<double>(i)) / total_steps);
      }
      run.round_seconds.push_back(seconds);
      done += static_cast<double>(steps);
    }
    if (round == 0 && options.repeats <= 0) {  // the default: as many rounds as fit (timing.hpp)
      double first_round = 0;
      for (size_t e : timed) first_round += runs[e].round_seconds.front();
      repeats = auto_rounds(first_round, kCompareBudget);
      total_steps = done + static_cast<double>(steps) * static_cast<double>(timed.size()) * (repeats - 1);
    }
  }
  return runs;
}

}  // namespace motus::compare
