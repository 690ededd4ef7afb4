#include "motus/precision/precision_report.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <fstream>
#include <iterator>
#include <string>
#include <stdexcept>

#include "motus/integrate/integrator_catalog.hpp"
#include "motus/plot/figure.hpp"
#include "motus/precision/odeint_peer.hpp"
#include "motus/precision/targets.hpp"
#include "motus/plot/html.hpp"
#include "motus/plot/write_failure.hpp"

namespace motus::precision {
namespace {

using motus::plot::html_escape;

std::string csv_text(const std::string& text) {
  std::string out;
  for (char c : text) out += c == ',' || c == '\n' || c == '\r' ? ';' : c;
  return out;
}

void write_file(const std::string& path, const std::string& text) {
  errno = 0;
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.flush();
  if (!out) throw std::runtime_error(plot::write_failure(path));
}

// Microseconds, or "not reached" (the method's curve never gets down to the target).
std::string micro(const std::optional<AtTarget>& at) {
  if (!at) return "not reached";
  return fmt::format("{}{:.3g} ({:.3g})", at->upper_bound ? "≤ " : "", 1e6 * at->seconds, 1e6 * at->median_seconds);
}

// A method's line (its place in the plots' palette, figure.cpp), the same in every diagram whoever
// else ran: Box2D and Bullet the colours compare gives them, motus's methods the other first sixteen
// in `motus list`'s order (the first in motus's own), Odeint's after them, a plug-in's methods after
// those. By its place among the curves drawn, Bullet's took motus's blue in one diagram and dark red
// in another.
int line_of(const Curve& curve, const std::vector<Curve>& curves) {
  if (curve.engine == "box2d") return plot::kEngineColour::box2d;
  if (curve.engine == "bullet") return plot::kEngineColour::bullet;
  const auto& builtin = all_integrators();
  const int motus_methods = static_cast<int>(builtin.size());
  const auto at = plot::integrator_colour;
  if (curve.engine == "motus")
    for (int m = 0; m < motus_methods; ++m)
      if (curve.method == builtin[static_cast<size_t>(m)].name) return at(m);
  const int odeint_from = at(motus_methods - 1) + 1;
  if (curve.engine == "odeint")
    for (int m = 0; m < static_cast<int>(std::size(kOdeintMethods)); ++m)
      if (curve.method == std::string("odeint:") + kOdeintMethods[m]) return odeint_from + m;
  int others = 0;  // a plug-in's methods, in their order
  for (const Curve& o : curves) {
    if (&o == &curve) break;
    others += o.engine != "motus" && o.engine != "odeint" && o.engine != "box2d" && o.engine != "bullet";
  }
  return odeint_from + static_cast<int>(std::size(kOdeintMethods)) + others;
}

std::vector<plot::Figure> diagrams(const ReportContext& c, const std::vector<Curve>& curves) {
  plot::Figure time, work;
  time.stem = "error_against_time";
  time.title = c.scene + ": error against run time";
  time.x_label = c.sweep.repeats == 1 ? std::string("run time [s] (CPU time, one timed round)")
                                       : "run time [s] (CPU time, the fastest of " + std::to_string(c.sweep.repeats) + " rounds)";
  work.stem = "error_against_evaluations";
  work.title = c.scene + ": error against derivative evaluations";
  work.x_label = "derivative (force) evaluations";
  for (plot::Figure* f : {&time, &work}) {
    f->y_label = "max |y - y_exact| at the end";
    f->x_scale = f->y_scale = plot::Scale::log;
    f->width = 1100;
    f->height = 620;
    f->key = "outside right top";
    f->note = "down and to the left is better; circles: motus's methods";
  }
  // (Said only of the peers drawn: a note that named Odeint, Box2D and Bullet on a diagram of motus's
  // methods alone read as if some of motus's dashed lines were theirs.)
  std::vector<std::string> peers_drawn;
  int peer_index = 0;
  std::vector<std::string> no_evaluations;  // methods whose every point made no evaluation
  bool plugin_drawn = false;
  for (const Curve& curve : curves) {
    if (!curve.unsupported.empty() || curve.points.empty()) continue;
    // motus's methods: solid, filled circles; a plug-in's (a student's): solid, open circles; the
    // peers: dashed, with squares, triangles and diamonds (never motus's circle).
    const bool peer = curve.engine == "odeint" || curve.engine == "box2d" || curve.engine == "bullet";
    const bool plugin = !peer && curve.engine != "motus";
    plugin_drawn = plugin_drawn || plugin;
    if (peer && std::find(peers_drawn.begin(), peers_drawn.end(), curve.engine) == peers_drawn.end())
      peers_drawn.push_back(curve.engine);
    constexpr int kPeerPoints[] = {5, 9, 11, 13};
    plot::Series s{curve.method, {}, {}};
    s.style = "linespoints";
    s.dashed = peer;
    s.point_type = peer ? kPeerPoints[peer_index++ % 4] : plugin ? 6 : 7;
    s.colour = line_of(curve, curves);
    plot::Series e = s;
    for (const Point& p : curve.points) {
      if (!p.failed.empty()) continue;
      s.x.push_back(p.seconds);
      s.y.push_back(p.error);
      // (A step with no force evaluates nothing, symplectic Euler among collisions: 0 has no
      // place on a log axis.)
      if (p.evaluations <= 0) continue;
      e.x.push_back(static_cast<double>(p.evaluations));
      e.y.push_back(p.error);
    }
    time.series.push_back(std::move(s));
    if (e.x.empty() && !time.series.back().x.empty()) {
      no_evaluations.push_back(curve.method);
    } else {
      work.series.push_back(std::move(e));
    }
  }
  if (plugin_drawn)
    for (plot::Figure* f : {&time, &work}) f->note += "; open circles: the plug-in's";
  if (!peers_drawn.empty()) {
    // (Box2D and Bullet said once, together when both are drawn.)
    const bool box2d = std::find(peers_drawn.begin(), peers_drawn.end(), "box2d") != peers_drawn.end();
    const bool bullet = std::find(peers_drawn.begin(), peers_drawn.end(), "bullet") != peers_drawn.end();
    std::string who;
    for (const auto& p : peers_drawn) {
      if (p == "odeint") who += (who.empty() ? "" : ", ") + std::string("Odeint on the same right-hand side");
      if (p == "box2d" || (p == "bullet" && !box2d))
        who += (who.empty() ? "" : ", ") + std::string(box2d && bullet ? "Box2D and Bullet" : box2d ? "Box2D" : "Bullet") +
               " with semi-implicit Euler";
    }
    // (Not "on dashed lines": motus's own lines after its first are dashed too, each its own way, so that
    // lines lying on each other show through; the points' shapes are what tell the engines apart.)
    for (plot::Figure* f : {&time, &work}) f->note += "; squares, triangles and diamonds: the peers (" + who + ")";
  }
  if (!no_evaluations.empty())
    work.note += "; not drawn, as they evaluate no force here: " + fmt::format("{}", fmt::join(no_evaluations, ", "));
  // A line drawn on an earlier one (the same evaluations, errors within 1 % of each other, less than a
  // pixel apart on a log axis of a few decades: symplectic Euler's two forms, Verlet's two, on Kepler)
  // hid it, and the legend showed a method that is nowhere to be seen: it says whose line it lies on.
  for (size_t b = 0; b < work.series.size(); ++b)
    for (size_t a = 0; a < b; ++a) {
      const plot::Series &first = work.series[a], &second = work.series[b];
      bool same = first.x == second.x && first.y.size() == second.y.size();
      for (size_t k = 0; same && k < first.y.size(); ++k)
        same = std::abs(first.y[k] - second.y[k]) <= 1e-2 * std::max(std::abs(first.y[k]), std::abs(second.y[k]));
      if (same) {
        work.series[b].name += " (on " + first.name + "'s line)";
        break;
      }
    }
  return {time, work};
}

}  // namespace

std::string precision_csv(const std::string& scene, const std::vector<Curve>& curves) {
  std::string csv = "scene,integrator,h,tolerance,steps,evaluations,t_end,error,seconds,engine,failed,median_seconds\n";
  for (const Curve& c : curves)
    for (const Point& p : c.points)
      csv += fmt::format("{},{},{:.17g},{},{},{},{:.17g},{:.6e},{:.6e},{},{},{:.6e}\n", csv_text(scene), csv_text(c.method), p.h,
                         c.adaptive ? fmt::format("{:.17g}", p.tolerance) : "", p.steps, p.evaluations, p.t_end,
                         p.failed.empty() ? p.error : NAN, p.failed.empty() ? p.seconds : NAN, csv_text(c.engine),
                         csv_text(p.failed), p.failed.empty() ? p.median_seconds : NAN);
  return csv;
}

std::string write_precision_report(const std::string& folder, const ReportContext& c, const std::vector<Curve>& curves) {
  write_file(folder + "/precision.csv", precision_csv(c.scene, curves));

  // targets.csv: every curve read at every target it reaches (one that never gets there has no row).
  std::string targets = "target,integrator,engine,seconds,median_seconds,evaluations,upper_bound\n";
  for (double target : c.targets)
    for (const Curve& curve : curves) {
      const auto at = at_target(curve, target);
      if (at)
        targets += fmt::format("{:g},{},{},{:.6e},{:.6e},{:.1f},{}\n", target, csv_text(curve.method), csv_text(curve.engine), at->seconds,
                               at->median_seconds, at->evaluations, at->upper_bound ? "yes" : "no");
    }
  write_file(folder + "/targets.csv", targets);

  const std::string warning = plot::draw(diagrams(c, curves), folder);

  std::vector<std::string> engines;  // the engines present, motus first
  for (const Curve& curve : curves)
    if (std::find(engines.begin(), engines.end(), curve.engine) == engines.end()) engines.push_back(curve.engine);

  std::string html;
  html += std::string(plot::kPageStart) + "motus bench precision: " + html_escape(c.scene) +
          "</title>\n<style>body{font-family:sans-serif;max-width:72em;margin:2em auto;padding:0 1em;color:#222}"
          "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #ccc;padding:.3em .6em;text-align:right}"
          "th{background:#f3f3f3}th[scope=row]{background:none;font-weight:normal}td:first-child,th:first-child{text-align:left}.no{color:#a00}.best{font-weight:bold}"
          "img{max-width:100%}code{background:#f3f3f3;padding:0 .2em}</style></head><body>\n";
  html += "<h1>" + html_escape(c.scene) + ": run time against error</h1>\n<p>" + html_escape(c.description) + "</p>\n";
  const auto ran = [&](const char* engine) { return std::find(engines.begin(), engines.end(), engine) != engines.end(); };
  const std::string engines_steps = ran("box2d") && ran("bullet") ? "; Box2D and Bullet run at dt = 1/30 … 1/960 s"
                                    : ran("box2d")                ? "; Box2D runs at dt = 1/30 … 1/960 s"
                                    : ran("bullet")               ? "; Bullet runs at dt = 1/30 … 1/960 s"
                                                                  : "";
  html += fmt::format(
      "<p>From t = {:g} {} to t = {:g} {}; error = the largest |y − y<sub>exact</sub>| over the state (positions and "
      "velocities, or y) where the run ended, against the scene's exact solution or reference states. Fixed-step "
      "methods take h = dt/2<sup>k</sup> (dt = {:g} {}, k = 0 … {}), adaptive ones rtol = atol = 10<sup>−3</sup> … "
      "10<sup>−13</sup>, {} per decade, first step dt{}. Each point runs once untimed (its error, steps and "
      "evaluations), then once in each of {} timed round{}, every engine in every round, taking turns (each round "
      "begins one method further on), all in one process. A run's time is CPU time from its first step to its last "
      "(what an engine builds before, its stepper, state or world, is left out alike); a point's is the fastest of its "
      "rounds, with the median beside it. {}{} Only ratios within this run mean anything on another machine.</p>\n",
      c.start, html_escape(c.time_unit), c.end, html_escape(c.time_unit), c.sweep.dt, html_escape(c.time_unit),
      c.sweep.levels - 1, c.sweep.per_decade, engines_steps, c.sweep.repeats, c.sweep.repeats == 1 ? "" : "s",
      html_escape(c.machine_load),
      c.busy_machine.empty() ? "" : " <strong>Warning:</strong> " + html_escape(c.busy_machine) + ".");

  // The fastest of each engine at each target.
  // (Each µs column names its engine: read alone, by a screen reader, "µs" would not say whose.)
  auto header = [](const std::string& text) { return "<th scope=\"col\">" + text + "</th>"; };
  html += "<h2 id=\"targets\">Targets: the fastest method at each target error</h2>\n<p>Each method's curve read at "
          "the target, interpolated on log–log axes between the two points that bracket it (≤: the method's cheapest "
          "point is already below the target; not reached: no point of its sweep is, and the smallest error any of the "
          "engine's points reached is given in brackets). The times are from the fastest runs of each point, the median "
          "runs' in brackets; the ratios likewise. –: no number, as there is no method to time.</p>\n"
          "<table aria-labelledby=\"targets\"><tr>" + header("target error");
  for (const auto& e : engines) html += header(html_escape(e) + " fastest") + header(html_escape(e) + " µs");
  for (size_t k = 1; k < engines.size(); ++k) html += header("motus ÷ " + html_escape(engines[k]));
  html += "</tr>\n";
  for (double target : c.targets) {
    html += fmt::format("<tr><th scope=\"row\">{:g}</th>", target);
    std::vector<std::optional<Fastest>> best;
    for (const auto& e : engines) {
      best.push_back(fastest(curves, e, target));
      html += best.back()            ? "<td>" + html_escape(best.back()->method) + "</td><td>" + micro(best.back()->at) + "</td>"
              : engine_runs(curves, e) ? "<td class=\"no\">" + not_reached_text(curves, e) + "</td><td>–</td>"
                                       : "<td class=\"no\">cannot run this scene</td><td>–</td>";
    }
    for (size_t k = 1; k < engines.size(); ++k)
      html += "<td>" + html_escape(engines[0] == "motus" ? ratio_text(best[0], best[k]) : "–") + "</td>";
    html += "</tr>\n";
  }
  html += "</table>\n";

  if (warning.empty()) {
    html += "<h2>Error against run time</h2><p><a href=\"error_against_time.png\"><img src=\"error_against_time.svg\" "
            "alt=\"error against run time, one line per method\"></a></p>\n";
    html += "<h2>Error against derivative evaluations</h2><p><a href=\"error_against_evaluations.png\"><img "
            "src=\"error_against_evaluations.svg\" alt=\"error against derivative evaluations, one line per "
            "method\"></a></p>\n";
  } else {
    html += "<p class=\"no\">" + html_escape(warning) + "</p>\n";
  }

  html += "<h2 id=\"every-method\">Every method at every target</h2>\n<table aria-labelledby=\"every-method\"><tr>" +
          header("method");
  for (double target : c.targets) html += header(fmt::format("{:g}: µs (median)", target));
  html += "</tr>\n";
  for (const Curve& curve : curves) {
    html += "<tr><th scope=\"row\">" + html_escape(curve.method) + "</th>";
    if (!curve.unsupported.empty()) {
      html += fmt::format("<td class=\"no\" colspan=\"{}\">cannot run this scene: {}</td></tr>\n", c.targets.size(),
                          html_escape(curve.unsupported));
      continue;
    }
    for (double target : c.targets) html += "<td>" + micro(at_target(curve, target)) + "</td>";
    html += "</tr>\n";
  }
  html += "</table>\n<h2>The methods</h2>\n<ul>\n";
  for (const Curve& curve : curves)
    html += "<li><code>" + html_escape(curve.method) + "</code>: " +
            html_escape(curve.description.empty() && !curve.unsupported.empty() ? "cannot run this scene: " + curve.unsupported
                                                                                : curve.description) +
            "</li>\n";
  html += "</ul>\n<p>Engines: ";
  for (size_t i = 0; i < c.versions.size(); ++i) html += (i ? "; " : "") + html_escape(c.versions[i]);
  html += ".";
  if (ran("odeint"))
    html += " Odeint's steppers keep their state in a std::array where its size is known at compile time. On one "
            "body under central gravity (Kepler) and on the strange attractors (Lorenz, Rössler, Chen, Thomas, Aizawa) "
            "they are given the right-hand side an Odeint user would write, the same formula in the same order as "
            "motus's, so the same steps and evaluations and the same errors to rounding; on any other scene they call motus's own right-hand side (the scene's "
            "system by its concrete type) through views of their state, which costs them more per evaluation than a "
            "hand-written one would. Their tolerances are in Odeint's "
            "error norm, so only errors reached are compared.";
  if (ran("box2d") || ran("bullet"))
    html += " Box2D and Bullet integrate with semi-implicit Euler: their lines lie along motus's "
            "<code>symplectic-euler</code>, a first-order method (error ∝ dt over a stretch of time; at a closed "
            "orbit's whole period its errors cancel to dt²).";
  html += "</p>\n";
  html += "<p>Data: <a href=\"precision.csv\">precision.csv</a> (every point), <a href=\"targets.csv\">targets.csv</a> "
          "(every method at every target); the diagrams are redrawn by <code>gnuplot -d figures.gp</code> in this "
          "folder.</p>\n</body></html>\n";
  write_file(folder + "/index.html", html);
  return warning;
}

}  // namespace motus::precision
