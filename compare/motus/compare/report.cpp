#include "motus/compare/report.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "motus/process/run_program.hpp"

namespace motus::compare {
namespace {

std::string html_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

const EngineRun* find_motus(const std::vector<EngineRun>& runs) {
  for (const auto& r : runs)
    if (r.engine == "motus" && r.supported) return &r;
  return nullptr;
}

// A report file that could not be written whole (a full disk) is an error naming it.
void check_written(std::ofstream& out, const std::string& path) {
  out.flush();
  if (!out) throw std::runtime_error(path + ": could not be written (disk full?)");
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  check_written(out, path);
}

nlohmann::json number_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

// The plotting script: one line per engine, relative energy error and momentum change
// against time, read from metrics.csv.
constexpr const char* kPlotScript = R"PY(# Written by `motus compare`: plots of metrics.csv, one line per engine.
import csv, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open("metrics.csv")))
engines = []
for r in rows:
    if r["engine"] not in engines:
        engines.append(r["engine"])

def series(engine, column):
    rs = [r for r in rows if r["engine"] == engine]
    return [float(r["t"]) for r in rs], [float(r[column]) for r in rs]

for name, column, label in [("energy.png", "energy_error", "(E - E0) / |E0|"),
                            ("momentum.png", "momentum_change", "|p - p0| / scale")]:
    fig, ax = plt.subplots(figsize=(7, 3.6), dpi=100)
    for e in engines:
        t, y = series(e, column)
        ax.plot(t, y, label=e, linewidth=1.4)
    ax.set_xlabel("t [s]")
    ax.set_ylabel(label)
    ax.grid(True, alpha=0.3)
    ax.legend()
    ax.set_title(sys.argv[1] + ": " + label)
    fig.tight_layout()
    fig.savefig(name)
)PY";

}  // namespace

std::string python_with_matplotlib() {
  for (const std::string& candidate : {std::string("/usr/bin/python3"), process::find_program("python3")})
    if (!candidate.empty() && process::run_program({candidate, "-c", "import matplotlib"}, "", "/dev/null").ok())
      return candidate;
  return "";
}

nlohmann::json summary_json(const ReportContext& c, const std::vector<EngineRun>& runs) {
  nlohmann::json j;
  j["scene"] = c.scene_name;
  j["file"] = c.scene_file;
  j["integrator"] = c.integrator;
  j["dt"] = c.dt;
  j["duration"] = c.duration;
  j["dimensions"] = c.dimensions;
  j["bodies"] = c.bodies;
  const EngineRun* motus = find_motus(runs);
  j["engines"] = nlohmann::json::array();
  for (const auto& r : runs) {
    nlohmann::json e;
    e["engine"] = r.engine;
    e["version"] = r.version;
    e["supported"] = r.supported;
    e["unsupported"] = r.unsupported;
    if (r.supported && !r.rows.empty()) {
      e["steps"] = r.steps;
      e["energy_drift"] = number_or_null(r.energy_drift());
      e["max_energy_error"] = number_or_null(r.max_energy_error());
      e["momentum_drift"] = number_or_null(r.momentum_drift());
      e["max_penetration"] = r.max_penetration();
      e["constraint_error"] = r.max_constraint_error();
      e["max_distance_from_motus"] = motus ? nlohmann::json(r.max_from_motus()) : nlohmann::json(nullptr);
      e["max_distance_from_exact"] = r.max_from_exact() >= 0 ? nlohmann::json(r.max_from_exact()) : nlohmann::json(nullptr);
      e["us_per_step"] = r.microseconds_per_step();
      e["time_relative_to_motus"] =
          motus && motus->microseconds_per_step() > 0 ? nlohmann::json(r.microseconds_per_step() / motus->microseconds_per_step())
                                                      : nlohmann::json(nullptr);
      e["energy"] = {{"initial", r.rows.front().total}, {"final", r.rows.back().total}};
      e["momentum"] = {{"initial", r.rows.front().momentum}, {"final", r.rows.back().momentum}};
    }
    e["settings"] = r.settings;
    e["notes"] = r.notes;
    j["engines"].push_back(e);
  }
  return j;
}

std::string write_report(const std::string& folder, const ReportContext& c, const std::vector<EngineRun>& runs) {
  // metrics.csv: every sample of every engine.
  {
    std::ofstream csv(folder + "/metrics.csv");
    csv << "engine,t,kinetic,potential,total,energy_error,momentum_change,px,py,pz,penetration,constraint_error,"
           "distance_from_motus,distance_from_exact\n";
    for (const auto& r : runs) {
      if (!r.supported) continue;
      const auto& first = r.rows.front();
      const double scale = std::max(r.scale_of_momentum, 1e-300);
      for (const auto& row : r.rows) {
        double change = 0;
        double p[3] = {0, 0, 0};
        for (size_t k = 0; k < row.momentum.size(); ++k) {
          change += (row.momentum[k] - first.momentum[k]) * (row.momentum[k] - first.momentum[k]);
          p[k] = row.momentum[k];
        }
        const double e_error = first.total != 0 ? (row.total - first.total) / std::abs(first.total) : row.total - first.total;
        csv << fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.6e},{:.6e},{:.17g},{:.17g},{:.17g},{:.6e},{:.6e},{:.6e},{}\n",
                           r.engine, row.t, row.kinetic, row.potential, row.total, e_error, std::sqrt(change) / scale, p[0],
                           p[1], p[2], row.penetration, row.constraint_error, row.from_motus,
                           row.from_exact >= 0 ? fmt::format("{:.6e}", row.from_exact) : "");
      }
    }
    check_written(csv, folder + "/metrics.csv");
  }
  const nlohmann::json summary = summary_json(c, runs);
  write_text(folder + "/summary.json", summary.dump(2) + "\n");
  write_text(folder + "/plot.py", kPlotScript);

  std::string warning;
  const std::string python = python_with_matplotlib();
  if (python.empty()) {
    warning = "plots skipped: no python3 with matplotlib found (apt-get install python3-matplotlib)";
  } else {
    // The scene's name is one argument of the script, never part of a command line.
    if (!process::run_program({python, "plot.py", c.scene_name}, folder, folder + "/plot.log").ok())
      warning = "plots failed: see " + folder + "/plot.log";
  }

  // index.html
  std::ofstream html(folder + "/index.html");
  html << "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>motus compare: " << html_escape(c.scene_name)
       << "</title>\n<style>body{font-family:sans-serif;max-width:60em;margin:2em auto;padding:0 1em;color:#222}"
          "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:.3em .6em;text-align:right}"
          "th{background:#f3f3f3}td:first-child,th:first-child{text-align:left}.no{color:#a00}"
          "img{max-width:100%}code{background:#f3f3f3;padding:0 .2em}</style></head><body>\n";
  html << "<h1>" << html_escape(c.scene_name) << "</h1>\n<p>" << html_escape(c.description) << "</p>\n";
  html << fmt::format("<p>{} bodies in {} dimensions; dt = {:g} s for {:g} s; motus integrator <code>{}</code>. "
                      "Every engine runs the same parsed scene in one process; every metric is computed by the same "
                      "code from each engine's positions and velocities.</p>\n",
                      c.bodies, c.dimensions, c.dt, c.duration, html_escape(c.integrator));
  html << "<table><tr><th>engine</th><th>energy drift</th><th>max |ΔE|/E₀</th><th>momentum drift</th>"
          "<th>max penetration [m]</th><th>constraint error</th><th>max distance from motus [m]</th>"
          "<th>µs per step</th><th>time / motus</th></tr>\n";
  for (const auto& e : summary["engines"]) {
    if (!e["supported"].get<bool>()) {
      std::string why;
      for (const auto& u : e["unsupported"]) why += html_escape(u.get<std::string>()) + "<br>";
      html << "<tr><td>" << html_escape(e["engine"].get<std::string>()) << "</td><td class=\"no\" colspan=\"8\">" << why
           << "</td></tr>\n";
      continue;
    }
    auto cell = [](const nlohmann::json& v, const char* format) {
      return v.is_null() ? std::string("–") : fmt::format(fmt::runtime(format), v.get<double>());
    };
    html << "<tr><td>" << html_escape(e["engine"].get<std::string>()) << "</td><td>" << cell(e["energy_drift"], "{:+.2e}")
         << "</td><td>" << cell(e["max_energy_error"], "{:.2e}") << "</td><td>" << cell(e["momentum_drift"], "{:.2e}")
         << "</td><td>" << cell(e["max_penetration"], "{:.2e}") << "</td><td>" << cell(e["constraint_error"], "{:.2e}")
         << "</td><td>" << cell(e["max_distance_from_motus"], "{:.2e}") << "</td><td>" << cell(e["us_per_step"], "{:.2f}")
         << "</td><td>" << cell(e["time_relative_to_motus"], "{:.2f}×") << "</td></tr>\n";
  }
  html << "</table>\n";
  if (!c.video.empty() || !c.contact_sheet.empty()) {
    html << "<h2>Side by side</h2>\n";
    if (!c.video.empty())
      html << "<video src=\"" << html_escape(c.video) << "\" controls loop muted style=\"max-width:100%\"></video>\n";
    if (!c.contact_sheet.empty())
      html << "<p><img src=\"" << html_escape(c.contact_sheet) << "\" alt=\"the engines side by side at three instants\"></p>\n";
  }
  if (warning.empty()) {
    html << "<h2>Energy</h2><img src=\"energy.png\" alt=\"relative energy error against time\">\n"
            "<h2>Momentum</h2><img src=\"momentum.png\" alt=\"momentum change against time\">\n";
  } else {
    html << "<p class=\"no\">" << html_escape(warning) << "</p>\n";
  }
  html << "<h2>Settings</h2>\n";
  for (const auto& e : summary["engines"]) {
    html << "<h3>" << html_escape(e["engine"].get<std::string>()) << " <small>(" << html_escape(e["version"].get<std::string>())
         << ")</small></h3><ul>\n";
    for (const auto& s : e["settings"]) html << "<li>" << html_escape(s.get<std::string>()) << "</li>\n";
    html << "</ul>\n";
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
  return warning;
}

}  // namespace motus::compare
