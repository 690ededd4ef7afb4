#include "motus/compare/report.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "motus/compare/explanations.hpp"
#include "motus/compare/replay.hpp"
#include "motus/exact/exact_solution.hpp"
#include "motus/plot/figure.hpp"
#include "motus/plot/html.hpp"
#include "motus/plot/write_failure.hpp"
#include "motus/simulation.hpp"

namespace motus::compare {
namespace {

using motus::plot::html_escape;

const EngineRun* find_motus(const std::vector<EngineRun>& runs) {
  for (const auto& r : runs)
    if (r.engine == "motus" && r.supported) return &r;
  return nullptr;
}

// A report file that could not be written whole (a full disk) is an error naming it.
void check_written(std::ofstream& out, const std::string& path) {
  out.flush();
  // (errno says why: the failing open or write set it — no such folder, no space left, ...)
  if (!out) throw std::runtime_error(plot::write_failure(path));
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  check_written(out, path);
}

// An engine's colour in every figure, whoever else ran: motus, Box2D and Bullet their own, a
// plug-in's column the next ones.
int colour_of(const std::vector<EngineRun>& runs, const EngineRun& r) {
  if (r.engine == "motus") return plot::kEngineColour::motus;
  if (r.engine == "box2d") return plot::kEngineColour::box2d;
  if (r.engine == "bullet") return plot::kEngineColour::bullet;
  int others = 0;
  for (const auto& o : runs) {
    if (&o == &r) break;
    others += o.engine != "motus" && o.engine != "box2d" && o.engine != "bullet";
  }
  return plot::kEngineColour::first_free + others;
}

// An engine's line: its colour, and a dash by its place among the runs: the first (motus) solid,
// then dashes, dots, and dash-dots. Engines that agree draw the same curve (free_fall's energy error
// is the same in all three): all solid, the last one drawn hid the others; now each shows through
// the gaps of those drawn over it. Each pattern repeats within 24 px, well inside the legend's
// sample line (about 35 px in the SVG): a longer one (40,20) showed there as a solid line, like motus's.
plot::Series engine_series(const std::vector<EngineRun>& runs, const EngineRun& r) {
  static const char* const kDashes[] = {"(12,6)", "(3,5)", "(12,4,3,4)"};
  plot::Series s{r.engine, {}, {}};
  s.colour = colour_of(runs, r);
  const long place = &r - runs.data();
  s.dash = place == 0 ? "solid" : kDashes[(place - 1) % 3];
  s.line_width = 2.0;
  return s;
}

// An engine that could not run the scene is in the legend all the same, saying why (its column
// of the table says so too; a figure looked at alone must not drop it).
plot::Series not_run(const std::vector<EngineRun>& runs, const EngineRun& r) {
  plot::Series s = engine_series(runs, r);
  s.none_because = "not supported";
  if (!r.unsupported.empty()) {
    const std::string& why = r.unsupported.front();
    const auto colon = why.find(": ");
    s.none_because += colon == std::string::npos ? "" : " (" + why.substr(colon + 2) + ")";
  }
  return s;
}

// The report's figures: the energy error of every engine (on a log axis of |ΔE/E₀|, or symlog
// when it changes sign), and the momenta where the scene keeps them.
std::vector<plot::Figure> figures(const ReportContext& c, const std::vector<EngineRun>& runs) {
  // A scene that loses energy by design (restitution below 1, damping, drag): what is drawn is each
  // engine's energy change, the physics and the error together, to be compared between engines.
  const bool kept = c.scene && c.scene->mechanical && conserves_energy(*c.scene);
  plot::Figure energy;
  energy.stem = "energy";
  energy.title = c.scene_name + (kept ? ": energy error against time" : ": energy change against time");
  energy.x_label = "t [s]";
  energy.x_from = 0;
  bool changes_sign = false, negative = false, positive = false;
  for (const auto& r : runs) {
    if (!r.supported) energy.series.push_back(not_run(runs, r));
    if (!r.supported || r.rows.empty()) continue;
    plot::Series s = engine_series(runs, r);
    const double e0 = r.rows.front().total, divisor = energy_divisor(runs, r);
    // (From the first sample after the start: at t = 0 the change is 0 by definition, not an
    // exact 0 a log axis would have to leave out.)
    for (const auto& row : r.rows) {
      if (&row == &r.rows.front()) continue;
      const double error = in_energy_unit(row.total - e0, divisor);
      s.x.push_back(row.t);
      s.y.push_back(error);
      negative = negative || error < 0;
      positive = positive || error > 0;
    }
    energy.series.push_back(std::move(s));
  }
  changes_sign = negative && positive;
  const bool joules = energy_in_joules(runs);  // (E₀ = 0: the changes themselves)
  // A scene that loses energy by design and loses a visible part of it: a linear axis of the signed
  // change. On a log axis of |E − E0| bouncing_balls' three engines (0.877, 0.889, 0.902 of E0 lost)
  // piled against its top edge, and on a symlog one ragdoll's lay on its bottom edge.
  double largest = 0;
  for (const auto& s : energy.series)
    for (double y : s.y)
      if (std::isfinite(y)) largest = std::max(largest, std::abs(y));
  const bool linear = !kept && (joules || largest >= 1e-2);
  if (linear) {
    energy.y_scale = plot::Scale::linear;
    energy.y_label = joules ? "E - E0 [J]" : "(E - E0) / |E0|";
  } else if (changes_sign) {
    // Linear within ±threshold: the decade of the smallest change drawn (so that every change
    // that is not 0 is on the logarithmic part, and no decade below the data takes up the axis),
    // but no finer than rounding in the energy (1e-16 of it).
    double smallest = INFINITY, rounding = 1e-16;
    for (const auto& r : runs)
      for (const auto& row : r.rows)
        if (joules && std::isfinite(row.total)) rounding = std::max(rounding, 1e-16 * std::abs(row.total));
    for (const auto& s : energy.series)
      for (double y : s.y)
        if (y != 0 && std::isfinite(y)) smallest = std::min(smallest, std::abs(y));
    energy.y_scale = plot::Scale::symlog;
    energy.symlog_threshold =
        std::max(rounding, std::isfinite(smallest) ? std::pow(10.0, std::floor(std::log10(smallest))) : rounding);
    energy.y_label = fmt::format("{}   (symlog: logarithmic beyond ±{:.0e}{})", joules ? "E - E0 [J]" : "(E - E0) / |E0|",
                                 energy.symlog_threshold, joules ? " J" : "");
  } else {
    energy.y_scale = plot::Scale::log;
    energy.y_label = joules ? "|E - E0| [J]" : "|E - E0| / |E0|";
    for (auto& s : energy.series)
      for (double& y : s.y) y = std::abs(y);
  }
  // (On a symlog axis "up" is not "more": below 0, a decade up is ten times less lost.)
  const bool sticks = c.scene && c.scene->mechanical && !c.scene->mechanical->sticks.empty();
  energy.note = kept ? (changes_sign ? "the scene keeps its energy: 0 is exact; each decade away from 0 is ten times more "
                                       "energy gained (up) or lost (down)"
                                     : "the scene keeps its energy: 0 is exact; each decade up is ten times more energy "
                                       "gained or lost")
                     : std::string("the scene loses energy by design (restitution below 1, damping or drag)") +
                           (sticks ? ", and each engine's handling of its sticks takes some, its own way" : "") +
                           ": compare the engines with each other, not with 0";
  std::vector<plot::Figure> all = {energy};

  auto change_of = [&](const char* stem, const char* what, bool angular) {
    plot::Figure f;
    f.stem = stem;
    f.title = c.scene_name + ": " + what + " change against time";
    f.x_label = "t [s]";
    f.x_from = 0;
    f.y_scale = plot::Scale::log;
    // One scale for every engine, from the first that ran (motus's, in double precision): the
    // size of L₀ (of p₀, or Σ m |v₀| when that is larger). A scene that starts with none (L₀ = 0)
    // is drawn in kg·m²/s (kg·m/s), and says so: a peer's L₀ of float rounding would make a
    // fraction of nothing.
    double scale = 0;
    for (const auto& r : runs) {
      if (!r.supported || r.rows.empty()) continue;
      const auto& first = angular ? r.rows.front().angular_momentum : r.rows.front().momentum;
      const double size = length_of_change({}, first);
      scale = angular ? size : std::max(size, r.scale_of_momentum);
      break;
    }
    f.y_label = std::string("|") + (angular ? "L - L0" : "p - p0") + "|" +
                (scale > 0 ? std::string(" / ") + (angular ? "|L0|" : "max(|p0|, sum m |v0|)")
                           : angular ? " [kg m^2/s]   (L0 = 0)" : " [kg m/s]   (nothing moves at the start)");
    for (const auto& r : runs) {
      if (!r.supported) f.series.push_back(not_run(runs, r));
      if (!r.supported || r.rows.empty()) continue;
      plot::Series s = engine_series(runs, r);
      const auto& first = angular ? r.rows.front().angular_momentum : r.rows.front().momentum;
      for (const auto& row : r.rows) {
        if (&row == &r.rows.front()) continue;  // (0 by definition at the start, as the energy's)
        const auto& now = angular ? row.angular_momentum : row.momentum;
        const double change = length_of_change(first, now);
        s.x.push_back(row.t);
        s.y.push_back(scale > 0 ? change / scale : change);
      }
      f.series.push_back(std::move(s));
    }
    f.note = "the scene keeps it exactly: what is drawn is each engine's own error";
    return f;
  };
  if (c.momentum_conserved) all.push_back(change_of("momentum", "momentum", false));
  if (c.angular_momentum_conserved) all.push_back(change_of("angular_momentum", "angular momentum", true));
  return all;
}

nlohmann::json number_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

// What the momentum columns measure, and their note (explanations.hpp), for a context that may
// have no scene (then a momentum in metres).
std::string momentum_quantity_of(const ReportContext& c) {
  return c.scene ? momentum_quantity(*c.scene) : "momentum";
}
std::string momentum_footnote_of(const ReportContext& c) {
  return momentum_footnote(c.scene ? *c.scene : SceneDescription{}, c.momentum_conserved);
}

}  // namespace

std::string microseconds_text(double us) {
  const char* format = us >= 100 ? "{:.0f}" : us >= 10 ? "{:.1f}" : us >= 1 ? "{:.2f}" : "{:.3g}";
  return fmt::format(fmt::runtime(format), us);
}

Conserved conserved_quantities(const SceneDescription& scene) {
  Conserved c;
  if (!scene.mechanical) return c;
  const auto& m = *scene.mechanical;
  const auto& f = m.forces;
  const bool closed = m.colliders.empty() && m.pins.empty() && f.gravity.empty() && f.drag.empty() && f.pendulums.empty();
  bool anchored = false, anchored_off_origin = false;
  for (const auto& s : f.springs)
    if (s.b < 0) {
      anchored = true;
      anchored_off_origin = anchored_off_origin || s.anchor != std::array<double, 3>{0, 0, 0};
    }
  bool central_off_origin = false;
  for (const auto& g : f.central_gravity) central_off_origin = central_off_origin || g.centre != std::array<double, 3>{0, 0, 0};
  c.momentum = closed && !anchored && f.central_gravity.empty();
  c.angular_momentum = closed && m.dimensions >= 2 && !anchored_off_origin && !central_off_origin;
  return c;
}

nlohmann::json summary_json(const ReportContext& c, const std::vector<EngineRun>& runs) {
  const MachineLoad& load = c.load;
  nlohmann::json j;
  j["scene"] = c.scene_name;
  j["file"] = c.scene_file;
  j["integrator"] = c.integrator;
  j["dt"] = c.dt;
  j["duration"] = c.duration;
  j["dimensions"] = c.dimensions;
  j["bodies"] = c.bodies;
  j["repeats"] = c.repeats;
  // The machine while the engines were timed: its cores and 1-minute load average (null: not known).
  j["cores"] = load.cores > 0 ? nlohmann::json(load.cores) : nlohmann::json(nullptr);
  j["load_average"] = {{"start", number_or_null(load.at_start)}, {"end", number_or_null(load.at_end)}};
  j["busy_machine"] = busy_machine(load);
  j["energy_unit"] = energy_in_joules(runs) ? "J" : "E0";  // energy_drift, max_energy_error: joules, or fractions of |E₀|
  // momentum_drift: a change in kg·m/s (kg·rad/s where the coordinate is an angle), or a fraction of the scale.
  const std::string quantity = momentum_quantity_of(c);
  j["momentum_unit"] = !momentum_in_kg_m_s(runs) ? "scale" : quantity == "momentum" ? "kg·m/s" : "kg·rad/s";
  j["momentum_quantity"] = quantity;  // "momentum", or "m·θ'" (a pendulum's coordinate is its angle)
  j["momentum_conserved"] = c.momentum_conserved;  // else the table marks the column "*"
  j["coordinate_unit"] = c.scene ? coordinate_unit(*c.scene) : "m";
  // The scene as written overlaps (balls, or a body and a wall): motus moves it apart before the first
  // step, and the penetration column counts that start. Said, not only done (absent: no overlap).
  if (const std::string start = initial_overlap_note(c.initial_overlap, true); !start.empty()) j["initial_overlap"] = start;
  const EngineRun* motus = find_motus(runs);
  const Timings motus_time = motus ? motus->microseconds_per_step() : Timings{};
  j["engines"] = nlohmann::json::array();
  for (const auto& r : runs) {
    nlohmann::json e;
    e["engine"] = r.engine;
    e["version"] = r.version;
    e["supported"] = r.supported;
    e["unsupported"] = r.unsupported;
    if (r.supported && !r.rows.empty()) {
      e["steps"] = r.steps;
      // When the energy stopped being finite (a run that blew up; null: it never did). The figures
      // that are not finite from then on are null below (JSON has no infinity).
      e["not_finite_from"] = number_or_null(r.not_finite_from());
      const double divisor = energy_divisor(runs, r);
      e["energy_drift"] = number_or_null(r.energy_drift(divisor));
      e["max_energy_error"] = number_or_null(r.max_energy_error(divisor));
      e["momentum_drift"] = number_or_null(r.momentum_drift());
      e["max_penetration"] = r.max_penetration();
      e["constraint_error"] = r.max_constraint_error();
      e["max_distance_from_motus"] = motus ? nlohmann::json(r.max_from_motus()) : nlohmann::json(nullptr);
      e["max_distance_from_exact"] = r.max_from_exact() >= 0 ? nlohmann::json(r.max_from_exact()) : nlohmann::json(nullptr);
      // CPU time per step over the timing rounds: the minimum, and the median and largest beside it.
      const Timings time = r.microseconds_per_step();
      auto or_null = [&](double x) { return time.rounds > 0 ? nlohmann::json(x) : nlohmann::json(nullptr); };
      e["us_per_step"] = or_null(time.min);
      e["us_per_step_median"] = or_null(time.median);
      e["us_per_step_max"] = or_null(time.max);
      // (One round has no spread: 0 % read as perfectly steady timings.)
      e["us_per_step_spread"] = time.rounds > 1 ? nlohmann::json(time.spread()) : nlohmann::json(nullptr);
      nlohmann::json rounds = nlohmann::json::array();
      for (double seconds : r.round_seconds) rounds.push_back(r.steps ? 1e6 * seconds / static_cast<double>(r.steps) : 0.0);
      e["us_per_step_rounds"] = rounds;
      const bool ratio = time.rounds > 0 && motus_time.min > 0;
      e["time_relative_to_motus"] = ratio ? nlohmann::json(time.min / motus_time.min) : nlohmann::json(nullptr);
      e["time_relative_to_motus_median"] =
          ratio && motus_time.median > 0 ? nlohmann::json(time.median / motus_time.median) : nlohmann::json(nullptr);
      e["energy"] = {{"initial", r.rows.front().total}, {"final", r.rows.back().total}};
      e["momentum"] = {{"initial", r.rows.front().momentum}, {"final", r.rows.back().momentum}};
    }
    e["settings"] = r.settings;
    e["notes"] = r.notes;
    j["engines"].push_back(e);
  }
  if (c.scene && c.scene->mechanical) {
    const auto exact = exact_answer(*c.scene, runs);
    std::string notice = what_to_notice(*c.scene, runs, exact);
    // A peer integrates with symplectic Euler; motus with what the scene or --integrator says. A
    // difference in accuracy may be the method's, not the engine's (kepler: velocity Verlet 0.014 m
    // from the orbit, the peers 0.058 m — and motus too, 0.058 m, with symplectic Euler).
    const bool motus_ran = std::any_of(runs.begin(), runs.end(), [](const EngineRun& r) { return r.engine == "motus" && r.supported; });
    const bool peer_ran = std::any_of(runs.begin(), runs.end(), [](const EngineRun& r) {
      return (r.engine == "box2d" || r.engine == "bullet") && r.supported;
    });
    // (Not with sticks or pins: motus projects them on Verlet only, so there is no like to compare with.)
    const bool projected = !c.scene->mechanical->sticks.empty() || !c.scene->mechanical->pins.empty();
    // The method by its name: the integrator shown may be annotated ("symplectic-euler (student:symplectic-euler
    // in student)": motus's own symplectic Euler beside the student's, the peers' method, which an audit saw
    // called another one). symplectic-euler-x is the other symplectic Euler, position first: not the peers'.
    const std::string method = c.method.empty() ? c.integrator : c.method;
    if (motus_ran && peer_ran && !projected && !method.empty() && method != "symplectic-euler")
      notice += " motus integrated with " + c.integrator +
                (method == "symplectic-euler-x"
                     ? ", symplectic Euler position first (x += v h, then v += a h), Box2D and Bullet with symplectic "
                       "Euler velocity first (v += a h, then x += v h; their own): another method, and part of any "
                       "difference is the method's; "
                     : ", Box2D and Bullet with symplectic Euler (their own): part of any difference is the method's; ") +
                "--integrator symplectic-euler compares like with like.";
    j["notice"] = notice;
    if (exact) {
      nlohmann::json x;
      x["t"] = exact->t;
      x["source"] = exact->source;
      x["bodies"] = nlohmann::json::array();
      for (size_t i = 0; i < exact->position.size(); ++i)
        x["bodies"].push_back({{"position", exact->position[i]}, {"velocity", exact->velocity[i]}});
      x["engines"] = nlohmann::json::array();
      for (const auto& e : exact->engines)
        x["engines"].push_back({{"engine", e.engine},
                                {"final_velocities", e.velocity},
                                {"max_speed_error", e.worst_speed_error},
                                {"max_speed_error_body", e.worst_body},
                                {"final_distance", e.worst_position_error}});
      j["exact"] = x;
    }
    j["definitions"] = nlohmann::json::array();
    for (const auto& d : column_definitions(*c.scene, c.samples, c.momentum_conserved, energy_in_joules(runs), c.initial_overlap))
      j["definitions"].push_back({{"column", d.column}, {"meaning", d.meaning}});
  }
  return j;
}

std::string draw_figures(const std::string& folder, const ReportContext& c, const std::vector<EngineRun>& runs) {
  return plot::draw(figures(c, runs), folder);
}

void write_report(const std::string& folder, const ReportContext& c, const std::vector<EngineRun>& runs,
                  const std::string& plots_line) {
  const MachineLoad& load = c.load;
  // metrics.csv: every sample of every engine.
  {
    std::ofstream csv(folder + "/metrics.csv");
    csv << "engine,t,kinetic,potential,total,energy_error,momentum_change,px,py,pz,penetration,constraint_error,"
           "distance_from_motus,distance_from_exact\n";
    const bool motus_ran = find_motus(runs) != nullptr;  // (else no distance from it: an empty cell)
    for (const auto& r : runs) {
      if (!r.supported) continue;
      const auto& first = r.rows.front();
      const double scale = r.momentum_scale();  // (the summary's momentum_drift's)
      const double divisor = energy_divisor(runs, r);
      for (const auto& row : r.rows) {
        const double change = length_of_change(first.momentum, row.momentum);
        double p[3] = {0, 0, 0};
        for (size_t k = 0; k < row.momentum.size(); ++k) p[k] = row.momentum[k];
        const double e_error = in_energy_unit(row.total - first.total, divisor);
        csv << fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.6e},{:.6e},{:.17g},{:.17g},{:.17g},{:.6e},{:.6e},{},{}\n",
                           r.engine, row.t, row.kinetic, row.potential, row.total, e_error, change / scale, p[0],
                           p[1], p[2], row.penetration, row.constraint_error,
                           motus_ran ? fmt::format("{:.6e}", row.from_motus) : "",
                           row.from_exact >= 0 ? fmt::format("{:.6e}", row.from_exact) : "");
      }
    }
    check_written(csv, folder + "/metrics.csv");
  }
  const nlohmann::json summary = summary_json(c, runs);
  // (A scene file's path or name need not be UTF-8: such bytes are written as U+FFFD.)
  write_text(folder + "/summary.json", summary.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  const std::string& warning = plots_line;

  // index.html
  std::ofstream html(folder + "/index.html");
  html << plot::kPageStart << "motus compare: " << html_escape(c.scene_name)
       << "</title>\n<style>body{font-family:sans-serif;max-width:75em;margin:2em auto;padding:0 1em;color:#222}"
          "table{border-collapse:collapse;margin:.5em 0}caption{text-align:left;font-weight:bold;padding:.3em 0}"
          "td,th{border:1px solid #ccc;padding:.3em .6em;text-align:right}td{white-space:nowrap}th{background:#f3f3f3}"
          "th[scope=row]{background:none}td:first-child,th:first-child{text-align:left}.no{color:#a00}"
          ".wide{overflow-x:auto}.notice{background:#eef4fb;border-left:4px solid #4285d6;padding:.6em .9em}"
          "dt{font-weight:bold;margin-top:.5em}dd{margin-left:1.5em}.dim{color:#666}"
          "img{max-width:100%}code{background:#f3f3f3;padding:0 .2em}"
       << (c.scene ? replay_style() : std::string()) << "</style></head><body>\n";
  html << "<h1>" << html_escape(c.scene_name) << "</h1>\n<p>" << html_escape(c.description) << "</p>\n";
  const long timed = std::count_if(runs.begin(), runs.end(), [](const EngineRun& r) { return r.supported; });
  std::string timing =
      c.repeats == 0 ? "No engine ran, so nothing was timed."
      : c.repeats == 1
          ? std::string("Times are CPU time per step over one timing round") +
                (timed > 1 ? ", the engines one after another." : ".")
          : fmt::format("Times are CPU time per step over {} timing rounds{}: the fastest round, with the median and "
                        "the spread (largest − smallest) / smallest beside it.",
                        c.repeats, timed > 1 ? ", the engines taking turns in each" : "");
  if (c.repeats > 0 && !machine_load_sentence(load).empty()) timing += " " + machine_load_sentence(load);
  // (The run ends after whole steps: kepler's 2π s at 0.01 s ends at 6.29 s, as motus run says.)
  const auto end = end_past_duration(c.scene ? c.scene->start_time : 0, c.duration, c.dt);
  html << fmt::format("<p>{} {} in {} dimension{}; dt = {:g} s for {:g} s{}; motus integrator <code>{}</code>. "
                      "Every engine runs the same parsed scene in one process; every metric is computed by the same "
                      "code from each engine's positions and velocities. {}</p>\n",
                      c.bodies, c.bodies == 1 ? "body" : "bodies", c.dimensions, c.dimensions == 1 ? "" : "s", c.dt,
                      c.duration,
                      end ? fmt::format(" ({} steps, ending at t = {:g} s)", fixed_step_count(c.duration, c.dt), *end) : "",
                      html_escape(c.integrator), timing);
  if (c.repeats > 0 && busy_machine(load)) {
    std::string warning = busy_machine_warning(load);
    warning[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(warning[0])));
    html << "<p class=\"no\">" << html_escape(warning) << ".</p>\n";
  }
  const bool exact_known = c.scene && has_exact_solution(*c.scene);
  const std::string unit = c.scene ? coordinate_unit(*c.scene) : "m";
  if (summary.contains("initial_overlap"))
    html << "<p class=\"no\"><b>Note:</b> " << html_escape(summary["initial_overlap"].get<std::string>())
         << ".</p>\n";
  if (summary.contains("notice"))
    html << "<p class=\"notice\"><b>What to notice.</b> " << html_escape(summary["notice"].get<std::string>()) << "</p>\n";
  const int columns = exact_known ? 11 : 10;
  // (Marked "*" where the column is not an engine's error; the note under the table says why.)
  const std::string momentum_heading =
      (momentum_quantity_of(c) == "momentum" ? std::string("momentum drift") + (momentum_in_kg_m_s(runs) ? " [kg·m/s]" : "")
                                             : std::string("m·θ' drift") + (momentum_in_kg_m_s(runs) ? " [kg·rad/s]" : "")) +
      (momentum_footnote_of(c).empty() ? "" : "*");
  // (Headers are column headers and each row's engine its row's header, for a screen reader's
  // "column, row" reading of a cell; headers may wrap, numbers not, so that the table fits the page.)
  auto header = [](const std::string& text) { return "<th scope=\"col\">" + text + "</th>"; };
  auto row_header = [](const std::string& text) { return "<th scope=\"row\">" + text + "</th>"; };
  html << "<div class=\"wide\"><table><caption>Each engine's run: its errors and its time per step</caption><tr>"
       << header("engine")
       << (energy_in_joules(runs) ? header("energy drift [J]") + header("max |ΔE| [J]")
                                  : header("energy drift") + header("max |ΔE|/E₀"))
       << header(momentum_heading)
       << header("max penetration [m]") << header("constraint error") << header("max distance from motus [" + unit + "]")
       << (exact_known ? header("max distance from exact [" + unit + "]") : "") << header("µs per step (min)")
       << header("median [µs]") << header("spread") << header("time / motus") << "</tr>\n";
  for (const auto& e : summary["engines"]) {
    if (!e["supported"].get<bool>()) {
      std::string why;
      for (const auto& u : e["unsupported"]) why += html_escape(u.get<std::string>()) + "<br>";
      html << "<tr>" << row_header(html_escape(e["engine"].get<std::string>())) << "<td class=\"no\" colspan=\"" << columns
           << "\" style=\"white-space:normal;text-align:left\">" << why << "</td></tr>\n";
      continue;
    }
    auto cell = [](const nlohmann::json& v, const char* format) {
      return v.is_null() ? std::string("–") : fmt::format(fmt::runtime(format), v.get<double>());
    };
    auto micros = [](const nlohmann::json& v) { return v.is_null() ? std::string("–") : microseconds_text(v.get<double>()); };
    html << "<tr>" << row_header(html_escape(e["engine"].get<std::string>())) << "<td>" << cell(e["energy_drift"], "{:+.2e}")
         << "</td><td>" << cell(e["max_energy_error"], "{:.2e}") << "</td><td>" << cell(e["momentum_drift"], "{:.2e}")
         << "</td><td>" << cell(e["max_penetration"], "{:.2e}") << "</td><td>" << cell(e["constraint_error"], "{:.2e}")
         << "</td><td>" << cell(e["max_distance_from_motus"], "{:.2e}")
         << (exact_known ? "</td><td>" + cell(e["max_distance_from_exact"], "{:.2e}") : std::string())
         << "</td><td>" << micros(e["us_per_step"]) << "</td><td>" << micros(e["us_per_step_median"])
         << "</td><td>"
         << (e["us_per_step_spread"].is_null() ? std::string("–")
                                               : fmt::format("{:.0f}%", 100 * e["us_per_step_spread"].get<double>()))
         << "</td><td>" << cell(e["time_relative_to_motus"], "{:.2f}×") << "</td></tr>\n";
  }
  html << "</table></div>\n";
  if (!momentum_footnote_of(c).empty())  // (a note on the table, not a row of it)
    html << "<p class=\"dim\">" << html_escape(momentum_footnote_of(c)) << "</p>\n";
  for (const auto& e : summary["engines"])
    if (e.contains("not_finite_from") && !e["not_finite_from"].is_null())
      html << fmt::format("<p class=\"no\">{} blew up: its energy is not finite from t = {:g} s on (its figures after "
                          "that are infinite, or not a number).</p>\n",
                          html_escape(e["engine"].get<std::string>()), e["not_finite_from"].get<double>());
  if (c.scene) {  // the engines side by side, played back in the page
    const std::vector<bool> in_view = engines_in_view(*c.scene, runs);
    write_replay(folder, *c.scene, runs, in_view);
    html << replay_section(*c.scene, runs, in_view);
  }
  if (summary.contains("exact")) {
    const auto& x = summary["exact"];
    html << "<h2 id=\"exact-answer\">The exact answer</h2>\n<p>" << html_escape(x["source"].get<std::string>()) << fmt::format(", at t = {:g} s", x["t"].get<double>())
         << ": each body's velocity [" << unit << "/s], then each engine's at the same time.</p>\n<div class=\"wide\">"
         << "<table aria-labelledby=\"exact-answer\"><tr>" << header("body") << header("exact");
    for (const auto& e : x["engines"]) html << header(html_escape(e["engine"].get<std::string>()));
    html << "</tr>\n";
    for (size_t i = 0; i < x["bodies"].size(); ++i) {
      html << "<tr>" << row_header(std::to_string(i)) << "<td>" << format_vector(x["bodies"][i]["velocity"].get<std::vector<double>>()) << "</td>";
      for (const auto& e : x["engines"]) html << "<td>" << format_vector(e["final_velocities"][i].get<std::vector<double>>()) << "</td>";
      html << "</tr>\n";
    }
    html << "<tr>" << row_header("largest |v − v_exact|") << "<td></td>";
    // (A run that blew up: "not a number", as the velocities say, not fmt's "-nan".)
    auto figure = [](const nlohmann::json& v) {
      return v.is_number() && std::isfinite(v.get<double>()) ? fmt::format("{:.2e}", v.get<double>())
             : v.is_number() && std::isinf(v.get<double>())  ? std::string("infinite")
                                                             : std::string("not a number");
    };
    for (const auto& e : x["engines"]) html << "<td>" << figure(e["max_speed_error"]) << " " << unit << "/s</td>";
    html << "</tr>\n<tr>" << row_header("largest |x − x_exact| at the end") << "<td></td>";
    for (const auto& e : x["engines"]) html << "<td>" << figure(e["final_distance"]) << " " << unit << "</td>";
    html << "</tr>\n</table></div>\n";
    if (c.scene && static_cast<long>(x["bodies"].size()) < static_cast<long>(c.scene->mechanical->bodies.size()))
      html << "<p class=\"dim\">The first " << x["bodies"].size() << " bodies are shown; the last two rows are over all of them.</p>\n";
  }
  if (summary.contains("definitions")) {
    html << "<h2>What the columns mean</h2>\n<dl>\n";
    for (const auto& d : summary["definitions"])
      html << "<dt>" << html_escape(d["column"].get<std::string>()) << "</dt><dd>" << html_escape(d["meaning"].get<std::string>())
           << "</dd>\n";
    html << "</dl>\n";
  }
  if (!c.first_and_last.empty())
    html << "<h2>At the start and at the end</h2>\n<p><img src=\"" << html_escape(c.first_and_last)
         << "\" alt=\"every engine at the first and the last instant\"></p>\n";
  if (!c.video.empty() || !c.contact_sheet.empty() || !c.pictures_note.empty()) {
    html << "<h2>Side by side</h2>\n";
    if (!c.pictures_note.empty()) html << "<p class=\"no\">" << html_escape(c.pictures_note) << "</p>\n";
    if (!c.video.empty())
      html << "<video src=\"" << html_escape(c.video) << "\" controls loop muted style=\"max-width:100%\">"
           << "<p>This browser does not play the video here: <a href=\"" << html_escape(c.video) << "\">"
           << html_escape(c.video) << "</a>.</p></video>\n";
    if (!c.contact_sheet.empty())
      html << "<p><img src=\"" << html_escape(c.contact_sheet) << "\" alt=\"the engines side by side at three instants\"></p>\n";
  }
  if (warning.empty()) {
    const bool kept = c.scene && c.scene->mechanical && conserves_energy(*c.scene);
    html << "<h2>Energy</h2><p><a href=\"energy.png\"><img src=\"energy.svg\" alt=\"the energy "
         << (kept ? "error" : "change") << " against time\"></a></p>\n";
    if (c.momentum_conserved)
      html << "<h2>Momentum</h2><p><a href=\"momentum.png\"><img src=\"momentum.svg\" alt=\"the momentum change against "
              "time\"></a></p>\n";
    if (c.angular_momentum_conserved)
      html << "<h2>Angular momentum</h2><p><a href=\"angular_momentum.png\"><img src=\"angular_momentum.svg\" alt=\"the "
              "angular momentum change against time\"></a></p>\n";
  } else {
    html << "<p class=\"no\">" << html_escape(warning) << "</p>\n";
  }
  html << "<h2>Settings</h2>\n";
  for (const auto& e : summary["engines"]) {
    html << "<h3>" << html_escape(e["engine"].get<std::string>()) << " <small>(" << html_escape(e["version"].get<std::string>())
         << ")</small></h3>\n";
    if (!e["supported"].get<bool>()) {  // (no settings: it never ran)
      std::vector<std::string> why;
      for (const auto& u : e["unsupported"]) why.push_back(html_escape(u.get<std::string>()));
      html << "<p>not run: " << fmt::format("{}", fmt::join(why, "; ")) << "</p>\n";
    }
    if (!e["settings"].empty()) {
      html << "<ul>\n";
      for (const auto& s : e["settings"]) html << "<li>" << html_escape(s.get<std::string>()) << "</li>\n";
      html << "</ul>\n";
    }
    if (!e["notes"].empty()) {
      html << "<p>Where its own limits bite:</p><ul>\n";
      for (const auto& n : e["notes"]) html << "<li>" << html_escape(n.get<std::string>()) << "</li>\n";
      html << "</ul>\n";
    }
  }
  html << "<p>Data: <a href=\"metrics.csv\">metrics.csv</a> (every sample), <a href=\"summary.json\">summary.json</a>. "
          "Fair settings, and how the peers integrate and collide: <code>docs/peers.md</code> in the motus sources.</p>\n"
          "</body></html>\n";
  check_written(html, folder + "/index.html");
}

}  // namespace motus::compare
