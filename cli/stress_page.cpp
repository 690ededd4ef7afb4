#include "stress_page.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "motus/plot/figure.hpp"
#include "motus/plot/html.hpp"
#include "motus/plot/write_failure.hpp"

namespace motus::cli::stress {
namespace {

using motus::plot::html_escape;

// A number for a CSV cell or a table: 17 significant digits in CSV, 3 on the page; "inf" as is.
std::string csv(double x) { return fmt::format("{:.17g}", x); }
std::string short_number(double x) {
  if (std::isinf(x)) return "∞";
  if (x == 0) return "0";
  return fmt::format("{:.3g}", x);
}
nlohmann::json number_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

const char* name(Integrator i) { return info(i).name; }
// A figure of one line a method (up to eleven), its legend below: taller, so that the plot keeps its
// height (eight entries and a three-line heading had left it 215 of 480 px for twenty decades; a
// pictures audit). At the right, the legend's long entries took half the width instead.
void wide(plot::Figure& f) {
  f.width = 1000;
  f.height = 760;
}

// Its colour, as bench precision draws it (the integrators' table is in the enum's order).
int colour_of(Integrator i) { return plot::integrator_colour(static_cast<int>(i)); }

class File {
public:
  explicit File(std::string path) : path_(std::move(path)), out_(path_, std::ios::binary) {}
  ~File() noexcept(false) {
    out_.flush();
    if (!out_ && std::uncaught_exceptions() == 0) throw std::runtime_error(plot::write_failure(path_));
  }
  template <class T>
  File& operator<<(const T& x) {
    out_ << x;
    return *this;
  }

private:
  std::string path_;
  std::ofstream out_;
};

// What a mass-ratio row's scene run says in place of its energy error, or "" when it has one to show.
std::string scene_run_says(const MassRatioRow& m, FailureNotes& notes) {
  if (!m.gas_failed.empty()) return notes.cell(m.gas_failed);
  if (m.gas_collisions == 0) return "no contact in the run";
  return "";
}

bool has(const Report& r, const std::string& section) {
  return std::find(r.sections.begin(), r.sections.end(), section) != r.sections.end();
}

// ---- CSV -------------------------------------------------------------------------------------

void write_csvs(const std::string& folder, const Report& r) {
  if (has(r, "stability")) {
    File f(folder + "/stability.csv");
    f << "integrator,limit_h,limit_omega_h,theory_omega_h,limit_over_theory,first_blowup_h,theory,skipped\n";
    for (const auto& s : r.stability) {
      const double z = r.omega ? *r.omega * s.limit : NAN;
      f << name(s.integrator) << ',' << (s.limit > 0 ? csv(s.limit) : "") << ',' << (r.omega && s.limit > 0 ? csv(z) : "") << ','
        << (s.theory.z > 0 ? csv(s.theory.z) : "") << ',' << (s.theory.z > 0 && s.limit > 0 ? csv(z / s.theory.z) : "") << ','
        << (s.first_blowup > 0 ? csv(s.first_blowup) : "") << ",\"" << s.theory.text << "\",\"" << s.skipped << "\"\n";
    }
    File t(folder + "/stability_trials.csv");
    t << "integrator,h,omega_h,max_energy_error,blown\n";
    for (const auto& s : r.stability)
      for (const auto& trial : s.trials)
        t << name(s.integrator) << ',' << csv(trial.h) << ',' << (r.omega ? csv(*r.omega * trial.h) : "") << ','
          << csv(trial.max_error) << ',' << (trial.blown ? "true" : "false") << '\n';
  }
  if (has(r, "drift")) {
    File f(folder + "/drift.csv");
    f << "integrator,step,t,energy_error,max_energy_error_since_previous_row\n";
    for (const auto& d : r.drift)
      for (const auto& s : d.samples)
        f << name(d.integrator) << ',' << s.step << ',' << csv(s.t) << ',' << csv(s.error) << ',' << csv(s.window_max) << '\n';
  }
  if (has(r, "stiffness")) {
    File f(folder + "/stiffness.csv");
    f << "integrator,factor,max_energy_error,blown\n";
    for (const auto& s : r.stiffness)
      for (const auto& run : s.runs)
        f << name(s.integrator) << ',' << csv(run.factor) << ',' << csv(run.max_error) << ',' << (run.blown ? "true" : "false") << '\n';
  }
  if (has(r, "mass_ratio")) {
    File f(folder + "/mass_ratio.csv");
    // (The scene's cells are empty where it was not run, and its energy error where its balls never met.)
    f << "integrator,ratio,pair_velocity_error,pair_energy_error,pair_momentum_error,pair_collisions,pair_failed,"
         "gas_steps,gas_collisions,gas_max_energy_error,gas_failed\n";
    for (const auto& m : r.mass_ratio) {
      f << name(m.integrator) << ',' << csv(m.ratio) << ',' << csv(m.pair.velocity_error) << ',' << csv(m.pair.energy_error) << ','
        << csv(m.pair.momentum_error) << ',' << m.pair.collisions << ",\"" << m.pair.failed << "\",";
      if (m.gas_measured)
        f << m.gas_steps << ',' << m.gas_collisions << ',' << (m.gas_collisions > 0 ? csv(m.gas_energy_error) : "") << ",\""
          << m.gas_failed << "\"\n";
      else
        f << ",,,\"\"\n";
    }
  }
  if (has(r, "speed")) {
    File f(folder + "/speed.csv");
    f << "integrator,radii_per_step,pair_steps,pair_order_kept,pair_inside,pair_ball_collisions,pair_max_energy_error,"
         "pair_failed,gas_steps,gas_outside,gas_max_overlap,gas_max_energy_error,gas_collisions,gas_failed\n";
    for (const auto& s : r.speed) {
      f << name(s.integrator) << ',' << csv(s.radii_per_step) << ',' << s.pair_steps << ',' << (s.pair_order_kept ? "true" : "false")
        << ',' << (s.pair_inside ? "true" : "false") << ',' << s.pair_ball_collisions << ',' << csv(s.pair_energy_error) << ",\""
        << s.pair_failed << "\",";
      if (s.gas_measured)
        f << s.gas_steps << ',' << (r.speed_container ? std::to_string(s.gas_outside) : "") << ',' << csv(s.gas_max_overlap) << ','
          << csv(s.gas_energy_error) << ',' << s.gas_collisions << ",\"" << s.gas_failed << "\"\n";
      else
        f << ",,,,,\"\"\n";
    }
  }
  if (has(r, "sticks")) {
    File f(folder + "/sticks.csv");
    f << "variant,ratio,steps,max_stick_error,final_stick_error,failed\n";
    for (const auto& s : r.sticks)
      f << '"' << s.variant << "\"," << csv(s.ratio) << ',' << s.steps << ',' << csv(s.max_error) << ',' << csv(s.final_error)
        << ",\"" << s.failed << "\"\n";
  }
}

// ---- figures ---------------------------------------------------------------------------------

std::vector<plot::Figure> figures(const Report& r) {
  std::vector<plot::Figure> all;
  const std::string who = r.scene_name + ": ";
  if (has(r, "stability")) {
    plot::Figure f;
    f.stem = "stability";
    // (With a damper the energy's change is mostly the physics: a stable run's loses all of it, and a
    // method near its limit, whose growth cancels the damping, looked the most accurate.)
    f.title = who + (r.loses_energy_by_design ? "energy change" : "energy error") + " of a " +
              std::to_string(r.settings.steps) + "-step run against the step";
    f.x_label = r.omega ? "ω h" : "h [s]";
    f.y_label = "largest |E - E0| / |E0| over the run";
    f.x_scale = f.y_scale = plot::Scale::log;
    wide(f);
    // The theory's limits, where a line should turn up: marked for the methods drawn (the note says them
    // too, but every blow-up falls in the one decade 1 to 10, which has no tick of its own).
    bool symplectic = false, yoshida = false, rk4 = false;
    for (const auto& s : r.stability) {
      if (!s.skipped.empty()) continue;
      symplectic |= s.integrator == Integrator::SymplecticEuler || s.integrator == Integrator::SymplecticEulerX ||
                    s.integrator == Integrator::Verlet || s.integrator == Integrator::VelocityVerlet;
      yoshida |= s.integrator == Integrator::Yoshida4;
      rk4 |= s.integrator == Integrator::Rk4;
    }
    // (Unlabelled: three limits within a factor of two sit too close for words beside each; the note names them.)
    if (r.omega) {
      if (yoshida) f.x_marks.push_back({1.5734, ""});
      if (symplectic) f.x_marks.push_back({2, ""});
      if (rk4) f.x_marks.push_back({2 * std::sqrt(2.0), ""});
    }
    for (const auto& s : r.stability) {
      if (!s.skipped.empty()) continue;
      plot::Series line{name(s.integrator), {}, {}, "linespoints"};
      line.colour = colour_of(s.integrator);
      for (const auto& t : s.trials) {
        line.x.push_back(r.omega ? *r.omega * t.h : t.h);
        line.y.push_back(t.max_error);
      }
      f.series.push_back(std::move(line));
    }
    // (Not "the points at the top": an orbit that escapes may blow up at an error of about 1.)
    f.note = fmt::format("blown up: not finite, |E - E0| > {:g} |E0|, or a bound orbit or swing no longer bound{}{}", r.settings.energy_factor,
                         r.omega ? "; grey dashes: the theory's limits, ωh = 1.573 (yoshida4), 2 (symplectic), 2√2 (rk4)" : "",
                         r.loses_energy_by_design ? "; the scene loses energy by design (a damper or drag): at 1, the "
                                                    "damping took it all; lower is not more accurate"
                                                  : "");
    all.push_back(std::move(f));
  }
  if (has(r, "drift")) {
    plot::Figure f;
    f.stem = "drift";
    f.title = who + fmt::format("energy error over {} steps of dt = {:g} s", r.settings.drift_steps, r.dt);
    f.x_label = "t [s]";
    f.y_label = "largest |E - E0| / |E0| since the previous point";
    f.x_scale = f.y_scale = plot::Scale::log;
    wide(f);
    for (const auto& d : r.drift) {
      if (!d.skipped.empty()) continue;
      plot::Series line{name(d.integrator), {}, {}};
      line.colour = colour_of(d.integrator);
      for (const auto& s : d.samples) line.x.push_back(s.t), line.y.push_back(s.window_max <= 100 ? s.window_max : NAN);
      f.series.push_back(std::move(line));
    }
    f.note = "flat: bounded (the symplectic methods); flat at 1: the energy lost; rising: a drift; a line stops where it "
             "blew up or passed 100 (off the chart)";
    f.gap_from = "off the chart from", f.gap_means = "above 100, or blew up";
    all.push_back(std::move(f));
  }
  if (has(r, "stiffness")) {
    plot::Figure f;
    f.stem = "stiffness";
    const std::string knob = r.stiffness_knob.substr(0, r.stiffness_knob.find(','));
    f.title = who + fmt::format("{} raised by decades at dt = {:g} s", knob, r.dt);
    f.x_label = "factor (" + knob + " times it)";
    f.y_label = "largest |E - E0| / |E0| over the run";
    f.x_scale = f.y_scale = plot::Scale::log;
    wide(f);
    f.y_to = 10 * r.settings.energy_factor;  // (the blow-ups' level below the frame, not on it)
    for (const auto& s : r.stiffness) {
      if (!s.skipped.empty()) continue;
      plot::Series line{name(s.integrator), {}, {}, "linespoints"};
      line.colour = colour_of(s.integrator);
      for (const auto& run : s.runs)
        line.x.push_back(run.factor), line.y.push_back(run.blown ? r.settings.energy_factor : run.max_error);
      f.series.push_back(std::move(line));
    }
    f.note = fmt::format("a run that blew up is drawn at {:g}, the blow-up factor", r.settings.energy_factor);
    all.push_back(std::move(f));
  }
  if (has(r, "mass_ratio")) {
    plot::Figure f;
    f.stem = "mass_ratio";
    f.title = who + "collisions between masses 1 and R";
    f.x_label = "mass ratio R";
    f.y_label = "relative error";
    f.x_scale = f.y_scale = plot::Scale::log;
    for (Integrator i : {Integrator::SymplecticEuler, Integrator::Verlet}) {
      plot::Series pair{std::string(name(i)) + ": pair, |v - v_formula| / u", {}, {}, "linespoints"};
      plot::Series gas{std::string(name(i)) + ": the scene, max |E - E0| / |E0|", {}, {}, "linespoints"};
      pair.colour = gas.colour = colour_of(i);  // (the method's colour; the scene's line dashed)
      gas.dashed = true;
      for (const auto& m : r.mass_ratio)
        if (m.integrator == i) {
          pair.x.push_back(m.ratio), pair.y.push_back(m.pair.failed.empty() ? m.pair.velocity_error : NAN);
          gas.x.push_back(m.ratio), gas.y.push_back(m.gas_failed.empty() && m.gas_collisions > 0 ? m.gas_energy_error : NAN);
        }
      if (!pair.x.empty()) f.series.push_back(std::move(pair));
      if (!pair.x.empty() && r.mass_ratio_scene) f.series.push_back(std::move(gas));
    }
    f.note = "a point missing from a line is exactly 0 (a log axis has no 0)";
    f.gap_from = "no value from", f.gap_means = "the run failed, or its balls never met: see the table";
    all.push_back(std::move(f));
  }
  if (has(r, "speed") && r.speed_scene) {  // (the figure is the scene's: the pair's outcome is a yes or no)
    plot::Figure f;
    f.stem = "speed";
    f.title = who + "balls moving many radii per step";
    f.x_label = "radii per step";
    f.y_label = "relative";
    f.x_scale = f.y_scale = plot::Scale::log;
    for (Integrator i : {Integrator::SymplecticEuler, Integrator::Verlet}) {
      plot::Series overlap{std::string(name(i)) + ": deepest overlap / contact distance", {}, {}, "linespoints"};
      plot::Series energy{std::string(name(i)) + ": max |E - E0| / |E0|", {}, {}, "linespoints"};
      overlap.colour = energy.colour = colour_of(i);  // (the method's colour; the energy's line dashed)
      energy.dashed = true;
      for (const auto& s : r.speed)
        if (s.integrator == i) {
          overlap.x.push_back(s.radii_per_step), overlap.y.push_back(s.gas_failed.empty() ? s.gas_max_overlap : NAN);
          energy.x.push_back(s.radii_per_step), energy.y.push_back(s.gas_failed.empty() ? s.gas_energy_error : NAN);
        }
      if (!overlap.x.empty() && r.speed_scene) f.series.push_back(std::move(overlap)), f.series.push_back(std::move(energy));
    }
    f.note = "the scene's balls with their velocities scaled; tunnelling is in the table";
    f.gap_from = "no value from", f.gap_means = "failed: see the table";
    all.push_back(std::move(f));
  }
  if (has(r, "sticks")) {
    plot::Figure f;
    f.stem = "sticks";
    f.title = who + "sticks between masses 1 and R (verlet)";
    f.x_label = "mass ratio R";
    f.y_label = "largest |length - rest| / rest over the run";
    f.x_scale = f.y_scale = plot::Scale::log;
    for (const auto& variant : r.stick_variants_measured) {
      plot::Series line{variant + " × R", {}, {}, "linespoints"};
      for (const auto& s : r.sticks)
        if (s.variant == variant) line.x.push_back(s.ratio), line.y.push_back(s.failed.empty() ? s.max_error : NAN);
      f.series.push_back(std::move(line));
    }
    f.note = "the stick error: what the projection sweeps leave of a stretch";
    f.gap_from = "no value from", f.gap_means = "the run failed: see the table";
    all.push_back(std::move(f));
  }
  return all;
}

}  // namespace

std::string FailureNotes::cell(const std::string& message) {
  auto at = std::find(notes_.begin(), notes_.end(), message);
  if (at == notes_.end()) at = notes_.insert(notes_.end(), message);
  return fmt::format("failed ({})", at - notes_.begin() + 1);
}

double theory_first_failure(const Report& r, Integrator integrator) {
  if (!r.omega) return 0;
  const StabilityTheory t = stability_theory(integrator, r.settings.steps, r.settings.energy_factor);
  if (t.z <= 0) return 0;
  for (double factor : stiffness_factors()) {
    const double omega_h = *r.omega * std::sqrt(factor) * r.dt;  // ω grows as √k; Euler's and midpoint's z: the run's
    // (At the limit itself: RK4's ωh = 2√2 is stable, the symplectic ones' ωh = 2 is not.)
    if (t.limit_included ? omega_h > t.z : omega_h >= t.z) return factor;
  }
  return 0;
}

nlohmann::json summary_json(const Report& r) {
  nlohmann::json j;
  j["scene"] = r.scene_name;
  j["file"] = r.scene_file;
  j["dt"] = r.dt;
  j["dimensions"] = r.dimensions;
  j["bodies"] = r.bodies;
  j["settings"] = {{"steps", r.settings.steps},
                   {"drift_steps", r.settings.drift_steps},
                   {"energy_factor", r.settings.energy_factor},
                   {"duration", r.settings.duration}};
  j["omega"] = r.omega ? nlohmann::json(*r.omega) : nlohmann::json(nullptr);
  j["sections"] = r.sections.empty() ? nlohmann::json::array() : nlohmann::json(r.sections);
  j["not_applied"] = nlohmann::json::object();
  for (const auto& [section, why] : r.not_applied) j["not_applied"][section] = why;
  j["cannot_run"] = nlohmann::json::object();
  for (const auto& [integrator, why] : r.cannot_run) j["cannot_run"][integrator] = why;
  if (has(r, "stability")) {
    j["stability"] = nlohmann::json::array();
    for (const auto& s : r.stability)
      j["stability"].push_back({{"integrator", name(s.integrator)},
                                {"skipped", s.skipped},
                                {"limit_h", s.limit > 0 ? nlohmann::json(s.limit) : nlohmann::json(nullptr)},
                                {"limit_omega_h", r.omega && s.limit > 0 ? nlohmann::json(*r.omega * s.limit) : nlohmann::json(nullptr)},
                                {"theory_omega_h", s.theory.z > 0 ? nlohmann::json(s.theory.z) : nlohmann::json(nullptr)},
                                {"theory", s.theory.text},
                                {"first_blowup_h", s.first_blowup > 0 ? nlohmann::json(s.first_blowup) : nlohmann::json(nullptr)},
                                {"trials", s.trials.size()}});
  }
  if (has(r, "drift")) {
    j["drift"] = nlohmann::json::array();
    for (const auto& d : r.drift)
      j["drift"].push_back({{"integrator", name(d.integrator)},
                            {"skipped", d.skipped},
                            {"steps", d.steps},
                            // (null where it was not measured, as the page's and the terminal's "–":
                            // a skipped integrator, or a run that blew up before its last tenth)
                            {"first_hundredth_max", d.skipped.empty() ? number_or_null(d.first_hundredth_max)
                                                                      : nlohmann::json(nullptr)},
                            {"last_tenth_max", d.skipped.empty() && d.blown.empty() ? number_or_null(d.last_tenth_max)
                                                                                    : nlohmann::json(nullptr)},
                            {"blown", d.blown},
                            {"energy_scale", number_or_null(d.energy_scale)},
                            {"last_tenth_max_abs", d.skipped.empty() && d.blown.empty() ? number_or_null(d.last_tenth_max_abs)
                                                                                        : nlohmann::json(nullptr)},
                            {"rounding_floor", number_or_null(d.rounding_floor)},
                            {"verdict", d.verdict}});
  }
  if (has(r, "stiffness")) {
    j["stiffness"] = {{"raised", r.stiffness_knob}, {"integrators", nlohmann::json::array()}};
    for (const auto& s : r.stiffness) {
      const double theory = theory_first_failure(r, s.integrator);
      j["stiffness"]["integrators"].push_back(
          {{"integrator", name(s.integrator)},
           {"skipped", s.skipped},
           {"first_failure", s.first_failure > 0 ? nlohmann::json(s.first_failure) : nlohmann::json(nullptr)},
           {"theory_first_failure", theory > 0 ? nlohmann::json(theory) : nlohmann::json(nullptr)}});
    }
  }
  if (has(r, "mass_ratio")) {
    j["mass_ratio"] = nlohmann::json::array();
    for (const auto& m : r.mass_ratio)
      j["mass_ratio"].push_back({{"integrator", name(m.integrator)},
                                 {"ratio", m.ratio},
                                 {"pair_velocity_error", m.pair.velocity_error},
                                 {"pair_energy_error", m.pair.energy_error},
                                 {"pair_momentum_error", m.pair.momentum_error},
                                 {"pair_collisions", m.pair.collisions},
                                 {"pair_failed", m.pair.failed},
                                 // (null where the scene was not run, or its balls never met: nothing measured)
                                 {"gas_measured", m.gas_measured},
                                 {"gas_steps", m.gas_steps},
                                 {"gas_collisions", m.gas_collisions},
                                 {"gas_max_energy_error", m.gas_measured && m.gas_collisions > 0 ? number_or_null(m.gas_energy_error)
                                                                                                 : nlohmann::json(nullptr)},
                                 {"gas_failed", m.gas_failed}});
  }
  if (has(r, "speed")) {
    j["speed"] = nlohmann::json::array();
    for (const auto& s : r.speed)
      j["speed"].push_back({{"integrator", name(s.integrator)},
                            {"radii_per_step", s.radii_per_step},
                            {"pair_order_kept", s.pair_order_kept},
                            {"pair_inside", s.pair_inside},
                            {"pair_ball_collisions", s.pair_ball_collisions},
                            {"pair_failed", s.pair_failed},
                            {"gas_measured", s.gas_measured},
                            {"gas_outside", s.gas_measured && r.speed_container ? nlohmann::json(s.gas_outside) : nlohmann::json(nullptr)},
                            {"gas_max_overlap", s.gas_measured ? nlohmann::json(s.gas_max_overlap) : nlohmann::json(nullptr)},
                            {"gas_max_energy_error", s.gas_measured ? number_or_null(s.gas_energy_error) : nlohmann::json(nullptr)},
                            {"gas_failed", s.gas_failed}});
  }
  if (has(r, "sticks")) {
    j["sticks"] = nlohmann::json::array();
    for (const auto& s : r.sticks)
      j["sticks"].push_back({{"variant", s.variant},
                             {"ratio", s.ratio},
                             {"max_stick_error", number_or_null(s.max_error)},
                             {"final_stick_error", number_or_null(s.final_error)},
                             {"failed", s.failed}});
  }
  return j;
}

std::string write_page(const std::string& folder, const Report& r) {
  write_csvs(folder, r);
  {
    File f(folder + "/summary.json");
    f << summary_json(r).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';  // (a path not in UTF-8)
  }
  const std::string warning = plot::draw(figures(r), folder);

  File h(folder + "/index.html");
  h << plot::kPageStart << "motus stress: " << html_escape(r.scene_name)
    << "</title>\n<style>body{font-family:sans-serif;max-width:62em;margin:2em auto;padding:0 1em;color:#222}"
       "table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ccc;padding:.25em .55em;text-align:right}"
       "th{background:#f3f3f3}th[scope=row]{background:none;font-weight:normal}td:first-child,th:first-child{text-align:left}.no{color:#a00}.ok{color:#070}"
       "img{max-width:100%}code{background:#f3f3f3;padding:0 .2em}</style></head><body>\n";
  h << "<h1>Stress test: " << html_escape(r.scene_name) << "</h1>\n<p>" << html_escape(r.description) << "</p>\n";
  h << fmt::format("<p>{} {} in {} dimension{}, the scene's dt = {:g} s. Every number below was measured by running "
                   "<code>motus::Simulation</code> on the scene or on a variant of it; the CSV files hold every run. "
                   "Sections: {}.</p>\n",
                   r.bodies, r.bodies == 1 ? "body" : "bodies", r.dimensions, r.dimensions == 1 ? "" : "s", r.dt,
                   r.sections.empty() ? std::string("none") : html_escape(fmt::format("{}", fmt::join(r.sections, ", "))));
  if (!r.not_applied.empty()) {
    h << "<p>Not measured on this scene:</p><ul>\n";
    for (const auto& [section, why] : r.not_applied) h << "<li><b>" << html_escape(section) << "</b>: " << html_escape(why) << "</li>\n";
    h << "</ul>\n";
  }
  if (!r.cannot_run.empty()) {
    h << "<p>Integrators that cannot run this scene:</p><ul>\n";
    for (const auto& [integrator, why] : r.cannot_run) h << "<li><code>" << html_escape(integrator) << "</code>: " << html_escape(why) << "</li>\n";
    h << "</ul>\n";
  }
  auto figure = [&](const std::string& stem, const std::string& alt) {
    if (warning.empty())
      h << "<p><a href=\"" << stem << ".png\"><img src=\"" << stem << ".svg\" alt=\"" << html_escape(alt) << "\"></a></p>\n";
  };
  // A table's failures, as notes below it (the cells say "failed (k)", as the terminal's).
  auto write_notes = [&](const FailureNotes& notes) {
    for (size_t k = 0; k < notes.notes().size(); ++k)
      h << "<p class=\"no\">(" << k + 1 << ") " << html_escape(notes.notes()[k]) << "</p>\n";
  };
  const std::string blown_rule = fmt::format("the energy is not finite, or |E − E₀| &gt; {:g}·|E₀|, or an orbit that was bound "
                                             "(E₀ &lt; 0) escapes (E ≥ 0), or a pendulum's swing goes over the top "
                                             "(E ≥ 2mg/L, its potential there)",
                                             r.settings.energy_factor);

  if (has(r, "stability")) {
    h << "<h2 id=\"stability-heading\">The largest stable step</h2>\n<p>For each integrator, runs of " << r.settings.steps
      << " steps from the scene's start, with h doubled from dt/1024 until a run blows up, then bisected 24 times between "
         "the last stable step and the first that blew up. Blown up: "
      << blown_rule << ". Theory: <code>tests/reference/integrators.md</code>, stability on x'' = −ω²x"
      << (r.omega ? fmt::format(" (here ω = {:g})", *r.omega) : std::string(" (not applicable: this scene is not an undamped oscillator)"))
      << ". Explicit Euler and midpoint have no stable step there: their energy grows by a factor every step, so a run of N steps "
         "stays under the factor only for h below a bound that shrinks as N grows.</p>\n";
    h << "<table aria-labelledby=\"stability-heading\"><tr><th scope=\"col\">integrator</th><th scope=\"col\">largest stable h [s]</th>" << (r.omega ? "<th scope=\"col\">ω h</th>" : "")
      << "<th scope=\"col\">theory</th><th scope=\"col\">measured / theory</th></tr>\n";
    for (const auto& s : r.stability) {
      if (!s.skipped.empty()) {
        h << "<tr><th scope=\"row\">" << name(s.integrator) << "</th><td colspan=\"" << (r.omega ? 4 : 3) << "\">" << html_escape(s.skipped) << "</td></tr>\n";
        continue;
      }
      const double z = r.omega ? *r.omega * s.limit : NAN;
      h << "<tr><th scope=\"row\">" << name(s.integrator) << "</th><td>"
        // (Seven figures, as the terminal's table: the bisection ends within a relative 1e-7 or so;
        // six printed symplectic Euler's 1.999998 as 2 beside its ωh of 1.999998.)
        << (s.limit > 0 ? fmt::format("{:.7g}", s.limit) : "none (blows up at every h tried)")
        << (s.first_blowup == 0 ? " (no blow-up found)" : "") << "</td>";
      if (r.omega) h << "<td>" << (s.limit > 0 ? fmt::format("{:.6f}", z) : "–") << "</td>";
      h << "<td>" << html_escape(s.theory.text) << "</td><td>"
        << (s.theory.z > 0 && s.limit > 0 ? fmt::format("{:.6f}", z / s.theory.z) : "–") << "</td></tr>\n";  // (as the terminal's)
    }
    h << "</table>\n";
    figure("stability", r.loses_energy_by_design ? "the energy change of each trial against its step (a damper's loss included)"
                                                 : "the energy error of each trial against its step");
    h << "<p>Data: <a href=\"stability.csv\">stability.csv</a> (the limits), <a href=\"stability_trials.csv\">stability_trials.csv</a> "
         "(every trial).</p>\n";
  }
  if (has(r, "drift")) {
    h << "<h2 id=\"drift-heading\">Long-run drift</h2>\n<p>" << r.settings.drift_steps << " steps of the scene's dt = " << fmt::format("{:g}", r.dt)
      << " s; the energy error is recorded about 20 times a decade of steps, each point the largest since the one before. "
         "Rounding: the largest |E − E₀| over the last tenth is within what rounding the state can do, 4ε of the energies' "
         "own scale |KE| + |PE| each step (for <code>verlet</code>, whose velocity is a difference of positions, also "
         "4ε·m|v||x|/h), added up over the run: judged so before anything else, since |E − E₀|/|E₀| is cancellation where "
         "the energies dwarf E₀. Bounded: the largest error over the last tenth of the run is at most 1.5 times that over "
         "its first hundredth.</p>\n";
    h << "<table aria-labelledby=\"drift-heading\"><tr><th scope=\"col\">integrator</th><th scope=\"col\">max, first hundredth</th><th scope=\"col\">max, last tenth</th><th scope=\"col\">verdict</th></tr>\n";
    for (const auto& d : r.drift) {
      if (!d.skipped.empty()) {
        h << "<tr><th scope=\"row\">" << name(d.integrator) << "</th><td colspan=\"3\">" << html_escape(d.skipped) << "</td></tr>\n";
        continue;
      }
      h << "<tr><th scope=\"row\">" << name(d.integrator) << "</th><td>" << short_number(d.first_hundredth_max) << "</td><td>"
        << (d.blown.empty() ? short_number(d.last_tenth_max) : "–") << "</td><td class=\""
        << (d.verdict == "bounded" || d.verdict.rfind("rounding", 0) == 0 ? "ok" : "no")
        << "\">" << html_escape(d.verdict) << "</td></tr>\n";
    }
    h << "</table>\n";
    figure("drift", "the energy error against time, log-log");
    h << "<p>Data: <a href=\"drift.csv\">drift.csv</a>.</p>\n";
  }
  if (has(r, "stiffness")) {
    h << "<h2 id=\"stiffness-heading\">Stiffness</h2>\n<p>Raised by decades, 1× to 10⁸×, at the scene's dt: " << html_escape(r.stiffness_knob) << ". Each run is "
      << r.settings.steps << " steps; blown up as above.";
    if (r.omega)
      h << " On an oscillator ω grows as √k, so theory says a method fails once ω√(factor)·dt passes its limit.";
    h << "</p>\n<table aria-labelledby=\"stiffness-heading\"><tr><th scope=\"col\">integrator</th><th scope=\"col\">first factor that fails</th>" << (r.omega ? "<th scope=\"col\">theory</th>" : "") << "</tr>\n";
    for (const auto& s : r.stiffness) {
      if (!s.skipped.empty()) {
        h << "<tr><th scope=\"row\">" << name(s.integrator) << "</th><td colspan=\"" << (r.omega ? 2 : 1) << "\">" << html_escape(s.skipped)
          << "</td></tr>\n";
        continue;
      }
      h << "<tr><th scope=\"row\">" << name(s.integrator) << "</th><td>" << (s.first_failure > 0 ? fmt::format("{:g}", s.first_failure) : "none up to 1e8")
        << "</td>";
      if (r.omega) {
        const double t = theory_first_failure(r, s.integrator);
        h << "<td>" << (t > 0 ? fmt::format("{:g}", t) : "none up to 1e8") << "</td>";
      }
      h << "</tr>\n";
    }
    h << "</table>\n";
    figure("stiffness", "the energy error against the stiffness factor");
    h << "<p>Data: <a href=\"stiffness.csv\">stiffness.csv</a>.</p>\n";
  }
  if (has(r, "mass_ratio")) {
    h << "<h2 id=\"mass_ratio-heading\">Mass ratio</h2>\n<p>Two ways, for masses 1 and R from 1:1 to 1:10⁶. <b>The pair</b>: two balls of the scene's radius "
         "meeting head-on at ±1 m/s, against the course's one-dimensional collision formula (<code>docs/course.md</code>, "
         "section 9) with the scene's restitution for <code>symplectic-euler</code>'s impulses, and with e = 0 for "
         "<code>verlet</code>, whose projected contacts are perfectly inelastic.";
    if (r.mass_ratio_scene)
      h << " <b>The scene</b>: every second body R times heavier, run for "
        << fmt::format("{:g}", r.settings.duration)
        << " s, or, when its balls have not met by then, until that long after they first do (at most the scene's "
           "duration); its ball–ball contacts are counted (impulses, or for <code>verlet</code> the contacts its "
           "projection begins), and a run in which none happened measured nothing and says so. With e = 1 its energy "
           "is kept by the impulses.";
    h << "</p>\n";
    h << "<table aria-labelledby=\"mass_ratio-heading\"><tr><th scope=\"col\">integrator</th><th scope=\"col\">R</th><th scope=\"col\">pair |v − v_formula|/u</th><th scope=\"col\">pair energy</th><th scope=\"col\">pair momentum</th>"
      << (r.mass_ratio_scene ? "<th scope=\"col\">scene contacts</th><th scope=\"col\">scene max |ΔE|/E₀</th>" : "") << "</tr>\n";
    FailureNotes notes;
    for (const auto& m : r.mass_ratio) {
      h << "<tr><th scope=\"row\">" << name(m.integrator) << "</th><td>" << fmt::format("{:g}", m.ratio) << "</td>";
      if (m.pair.failed.empty())
        h << "<td>" << short_number(m.pair.velocity_error) << "</td><td>" << short_number(m.pair.energy_error) << "</td><td>"
          << short_number(m.pair.momentum_error) << "</td>";
      else
        h << "<td colspan=\"3\" class=\"no\">" << notes.cell(m.pair.failed) << "</td>";
      if (r.mass_ratio_scene) {
        const std::string says = scene_run_says(m, notes);
        h << "<td>" << m.gas_collisions << "</td>"
          << (says.empty() ? "<td>" + short_number(m.gas_energy_error) : "<td class=\"no\">" + html_escape(says)) << "</td>";
      }
      h << "</tr>\n";
    }
    h << "</table>\n";
    write_notes(notes);
    figure("mass_ratio", "errors against the mass ratio");
    h << "<p>Data: <a href=\"mass_ratio.csv\">mass_ratio.csv</a>.</p>\n";
  }
  if (has(r, "speed")) {
    h << "<h2 id=\"speed-heading\">Speed</h2>\n<p>From 1 to 10⁴ radii per step. <b>Tunnelling</b>: in a box of 40 radii, a ball shot along the box's "
         "middle line at a resting ball; both move on that line only, so if the moving ball is ever found beyond the other it "
         "went through it. <b>The scene</b>: its balls with every velocity scaled so that the fastest moves that many radii a "
         "step, for about three crossings of the container (3 to 300 steps): balls found outside the container, the deepest "
         "overlap of two balls after a step, and the energy.</p>\n";
    // (Only the columns that measure something: a scene at rest has no scene rows, and one with no
    // box no balls outside it; both are listed under "not measured".)
    const bool outside = r.speed_scene && r.speed_container;
    h << "<table aria-labelledby=\"speed-heading\"><tr><th scope=\"col\">integrator</th><th scope=\"col\">radii/step</th><th scope=\"col\">pair: order kept</th><th scope=\"col\">pair: in the box</th>"
         "<th scope=\"col\">pair: collisions</th>"
      << (outside ? "<th scope=\"col\">scene: outside</th>" : "")
      << (r.speed_scene ? "<th scope=\"col\">scene: deepest overlap</th><th scope=\"col\">scene: max |ΔE|/E₀</th>" : "") << "</tr>\n";
    FailureNotes notes;
    for (const auto& s : r.speed) {
      h << "<tr><th scope=\"row\">" << name(s.integrator) << "</th><td>" << fmt::format("{:g}", s.radii_per_step) << "</td>";
      if (!s.pair_failed.empty())
        h << "<td colspan=\"3\" class=\"no\">" << notes.cell(s.pair_failed) << "</td>";
      else
        h << "<td class=\"" << (s.pair_order_kept ? "ok\">yes" : "no\">no: it went through") << "</td><td class=\""
          << (s.pair_inside ? "ok\">yes" : "no\">no") << "</td><td>" << s.pair_ball_collisions << "</td>";
      if (r.speed_scene) {
        if (!s.gas_failed.empty())
          h << "<td colspan=\"" << (outside ? 3 : 2) << "\" class=\"no\">" << notes.cell(s.gas_failed) << "</td>";
        else
          h << (outside ? "<td>" + std::to_string(s.gas_outside) + "</td>" : "") << "<td>" << short_number(s.gas_max_overlap)
            << "</td><td>" << short_number(s.gas_energy_error) << "</td>";
      }
      h << "</tr>\n";
    }
    h << "</table>\n";
    write_notes(notes);
    if (r.speed_scene)     figure("speed", "overlap and energy error against the speed");
    h << "<p>Data: <a href=\"speed.csv\">speed.csv</a>.</p>\n";
  }
  if (has(r, "sticks")) {
    h << "<h2 id=\"sticks-heading\">Sticks between very different masses</h2>\n<p>The scene with "
         "<b>every second body</b> R times heavier (its sticks join a light and a heavy end), and with <b>the last body</b> R times "
         "heavier (one heavy weight on light sticks), as far as each joins masses 1 and R (see above), for "
      << fmt::format("{:g}", r.settings.duration) << " s (at most the scene's duration), with <code>verlet</code> and the scene's "
         "projection sweeps. The stick error is the largest |length − rest length| / rest length over the sticks and the run.</p>\n";
    h << "<table aria-labelledby=\"sticks-heading\"><tr><th scope=\"col\">variant</th><th scope=\"col\">R</th><th scope=\"col\">max stick error</th><th scope=\"col\">at the end</th></tr>\n";
    FailureNotes notes;
    for (const auto& s : r.sticks)
      h << "<tr><th scope=\"row\">" << html_escape(s.variant) << "</th><td>" << fmt::format("{:g}", s.ratio) << "</td><td>"
        << (s.failed.empty() ? short_number(s.max_error) : notes.cell(s.failed)) << "</td><td>" << short_number(s.final_error) << "</td></tr>\n";
    h << "</table>\n";
    write_notes(notes);
    figure("sticks", "the stick error against the mass ratio");
    h << "<p>Data: <a href=\"sticks.csv\">sticks.csv</a>.</p>\n";
  }
  if (!warning.empty()) h << "<p class=\"no\">" << html_escape(warning) << "</p>\n";
  h << "<p>All numbers: <a href=\"summary.json\">summary.json</a>. The figures are drawn by gnuplot from "
       "<code>figures.gp</code> and <code>figures.dat</code> beside them. What each section does: <code>docs/cli.md</code>, "
       "\"motus stress\", in the motus sources.</p>\n</body></html>\n";
  return warning;
}

}  // namespace motus::cli::stress
