#include "motus/compare/replay.hpp"
#include "motus/compare/explanations.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "motus/compare/replay_js.hpp"  // kReplayJs: compare/replay/replay.js, generated at build time
#include "motus/plot/figure.hpp"
#include "motus/plot/html.hpp"
#include "motus/plot/write_failure.hpp"
#include "motus/render/shared_view.hpp"

namespace motus::compare {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

using motus::plot::html_escape;

void check_written(std::ofstream& out, const std::string& path) {
  out.flush();
  // (errno says why: the failing open or write set it — no such folder, no space left, ...)
  if (!out) throw std::runtime_error(plot::write_failure(path));
}

// JSON (and so JavaScript) text; bytes that are not UTF-8 in a name become U+FFFD.
std::string dump(const nlohmann::ordered_json& j) { return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace); }

struct Bounds {
  double x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf;
  bool empty() const { return x0 > x1; }
  void add(double x, double y, double r = 0) {
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(r)) return;
    x0 = std::min(x0, x - r), x1 = std::max(x1, x + r);
    y0 = std::min(y0, y - r), y1 = std::max(y1, y + r);
  }
};

// Which bodies are drawn: every `stride`-th, from body 0.
long body_stride(size_t bodies) {
  return std::max(1L, static_cast<long>((static_cast<long>(bodies) + kReplayBodyLimit - 1) / kReplayBodyLimit));
}

const EngineRun* longest_run(const std::vector<EngineRun>& runs) {
  const EngineRun* best = nullptr;
  for (const auto& r : runs)
    if (r.supported && (!best || r.frames.size() > best->frames.size())) best = &r;
  return best;
}

// The frame energy error (E − E₀)/|E₀|, or E − E₀ when E₀ is 0 (as in metrics.csv).
double energy_error(double e, double e0) { return e0 != 0 ? (e - e0) / std::abs(e0) : e - e0; }

template <typename Buffer>
void put_number(Buffer& out, double x, int digits) {
  if (std::isfinite(x))
    fmt::format_to(std::back_inserter(out), "{:.{}g}", x, digits);
  else
    fmt::format_to(std::back_inserter(out), "null");
}

}  // namespace

std::vector<bool> engines_in_view(const SceneDescription& scene, const std::vector<EngineRun>& runs) {
  const auto& m = *scene.mechanical;
  std::vector<bool> in_view;
  size_t reference = runs.size();  // the first engine with frames (motus, when it ran)
  for (size_t e = 0; e < runs.size(); ++e) {
    in_view.push_back(runs[e].supported && !runs[e].frames.empty());
    if (in_view.back() && reference == runs.size()) reference = e;
  }
  const auto states = [&](size_t e, const auto& visit) {
    for (const auto& f : runs[e].frames)
      if (f.x.size() >= m.bodies.size() * static_cast<size_t>(m.dimensions)) visit(f.x);
  };
  return render::in_a_shared_view(scene, states, reference, std::move(in_view));
}

ReplayView replay_view(const SceneDescription& scene, const std::vector<EngineRun>& runs, const std::vector<bool>& in_view) {
  const auto& m = *scene.mechanical;
  const int d = m.dimensions;
  Bounds b;
  for (const auto& box : m.colliders.boxes) {
    b.add(box.min[0], d == 1 ? 0 : box.min[1]);
    b.add(box.max[0], d == 1 ? 0 : box.max[1]);
  }
  for (const auto& s : m.colliders.segments) b.add(s.a[0], s.a[1]), b.add(s.b[0], s.b[1]);
  if (b.empty()) {
    for (size_t e = 0; e < runs.size(); ++e) {
      if (!in_view[e]) continue;
      for (const auto& f : runs[e].frames)
        for (size_t i = 0; i < m.bodies.size() && (i + 1) * static_cast<size_t>(d) <= f.x.size(); ++i)
          b.add(f.x[i * d], d == 1 ? 0 : f.x[i * d + 1], m.bodies[i].radius);
    }
    if (b.empty())  // no frames: the start
      for (const auto& body : m.bodies) b.add(body.position[0], d == 1 ? 0 : body.position[1], body.radius);
    // Each plane seen edge-on (its normal in the picture's plane): the point of it nearest to the
    // bodies, so that the ground they bounce on is in view.
    if (!b.empty()) {
      const double cx = (b.x0 + b.x1) / 2, cy = (b.y0 + b.y1) / 2;
      for (const auto& p : m.colliders.planes) {
        const double nx = p.normal[0], ny = d == 1 ? 0 : p.normal[1], length = std::hypot(nx, ny);
        if (length < 0.5) continue;
        const double along = (nx * cx + ny * cy) / length - p.offset / length;
        b.add(cx - along * nx / length, cy - along * ny / length);
      }
    }
  }
  if (b.empty()) b.add(0, 0);
  return {b.x0, b.y0, b.x1, b.y1};
}

void write_replay(const std::string& folder, const SceneDescription& scene, const std::vector<EngineRun>& runs,
                  const std::vector<bool>& in_view) {
  {
    const std::string path = folder + "/replay.js";
    std::ofstream js(path, std::ios::binary);
    js << kReplayJs;
    check_written(js, path);
  }
  const auto& m = *scene.mechanical;
  const int d = m.dimensions;
  const size_t n = m.bodies.size();
  const long stride = body_stride(n);
  const ReplayView view = replay_view(scene, runs, in_view);

  // Digits enough for a ten-thousandth of the view at the largest coordinate written (6 at least).
  double largest = 0;
  for (const auto& r : runs)
    if (r.supported)
      for (const auto& f : r.frames)
        for (double x : f.x)
          if (std::isfinite(x)) largest = std::max(largest, std::abs(x));
  const double extent = std::max({view.x1 - view.x0, view.y1 - view.y0, 1e-300});
  const int digits =
      largest > 0 ? std::clamp(static_cast<int>(std::ceil(std::log10(largest / extent))) + 5, 6, 12) : 6;

  nlohmann::ordered_json head;
  head["format"] = 1;
  head["scene"] = scene.name;
  head["dimensions"] = d;
  head["bodies"] = n;
  head["stride"] = stride;  // bodies 0, stride, 2·stride, ... are the ones written and drawn
  head["view"] = {view.x0, view.y0, view.x1, view.y1};
  nlohmann::ordered_json radius = nlohmann::ordered_json::array(), color = nlohmann::ordered_json::array();
  for (size_t i = 0; i < n; i += static_cast<size_t>(stride)) {
    radius.push_back(m.bodies[i].radius);
    // (render/motus/render/frame.cpp's body_color, after the engines' three colours, as the drawn frames
    // take them: DrawOptions::first_body_colour. head_on's orange ball read as Box2D's.)
    color.push_back((i + plot::kEngineColour::first_free) % 8);
  }
  head["radius"] = radius;
  head["color"] = color;
  nlohmann::ordered_json planes = nlohmann::ordered_json::array(), boxes = nlohmann::ordered_json::array();
  nlohmann::ordered_json segments = nlohmann::ordered_json::array();
  for (const auto& p : m.colliders.planes) planes.push_back({p.normal[0], p.normal[1], p.normal[2], p.offset});
  for (const auto& box : m.colliders.boxes)
    boxes.push_back({box.min[0], box.min[1], box.min[2], box.max[0], box.max[1], box.max[2]});
  for (const auto& s : m.colliders.segments) segments.push_back({s.a[0], s.a[1], s.b[0], s.b[1]});
  head["walls"] = {{"planes", planes}, {"boxes", boxes}, {"segments", segments}};
  nlohmann::ordered_json sticks = nlohmann::ordered_json::array(), pins = nlohmann::ordered_json::array();
  for (const auto& s : m.sticks)  // both ends drawn, as indices among the bodies written
    if (s.a % stride == 0 && s.b % stride == 0) sticks.push_back({s.a / stride, s.b / stride});
  for (const auto& p : m.pins) pins.push_back({p.position[0], d == 1 ? 0.0 : p.position[1]});
  head["sticks"] = sticks;
  head["pins"] = pins;

  const std::string path = folder + "/replay-data.js";
  std::ofstream out(path, std::ios::binary);
  std::string text = dump(head);
  text.pop_back();  // the closing brace: the engines follow
  out << "// motus compare: the replay's data, drawn by replay.js (generated by compare/motus/compare/replay.cpp).\n"
         "// One object: the scene's geometry, then per engine the frame times t, positions x (every written body's\n"
         "// coordinates, frame by frame) and the energy error (E - E0)/|E0| of each frame.\n"
      << "window.MOTUS_REPLAY = " << text << ",\"engines\":[";
  fmt::memory_buffer buffer;
  for (size_t k = 0; k < runs.size(); ++k) {
    const EngineRun& r = runs[k];
    const bool has_frames = r.supported && !r.frames.empty();
    nlohmann::ordered_json e;
    e["name"] = r.engine;
    e["version"] = r.version;
    e["supported"] = r.supported;
    e["unsupported"] = r.unsupported;
    const double e0 = r.frame_energies.empty() ? 0 : r.frame_energies.front();
    e["energy_relative"] = e0 != 0;
    std::string engine = dump(e);
    engine.pop_back();
    out << (k ? ",\n" : "\n") << engine;
    buffer.clear();
    fmt::format_to(std::back_inserter(buffer), ",\"t\":[");
    if (has_frames)
      for (size_t f = 0; f < r.frames.size(); ++f) {
        if (f) buffer.push_back(',');
        put_number(buffer, r.frames[f].t, 12);
      }
    fmt::format_to(std::back_inserter(buffer), "],\"energy_error\":[");
    if (has_frames)
      for (size_t f = 0; f < r.frames.size(); ++f) {
        if (f) buffer.push_back(',');
        put_number(buffer, f < r.frame_energies.size() ? energy_error(r.frame_energies[f], e0) : kInf, 4);
      }
    fmt::format_to(std::back_inserter(buffer), "],\"x\":[");
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    if (has_frames)
      for (size_t f = 0; f < r.frames.size(); ++f) {
        buffer.clear();
        buffer.append(std::string_view(f ? ",\n[" : "\n["));
        const auto& x = r.frames[f].x;
        bool first = true;
        for (size_t i = 0; i < n; i += static_cast<size_t>(stride))
          for (int c = 0; c < d; ++c) {
            if (!first) buffer.push_back(',');
            first = false;
            const size_t at = i * static_cast<size_t>(d) + static_cast<size_t>(c);
            put_number(buffer, at < x.size() ? x[at] : kInf, digits);
          }
        buffer.push_back(']');
        out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      }
    out << "]}";
  }
  out << "\n]};\n";
  check_written(out, path);
}

std::string replay_style() {
  // The layout is fixed in pixels so that a picture of the page can be read back (the rule is in
  // compare/replay/replay.js and docs/cli.md); everything is scoped to #replay. The last rule keeps
  // what the script has not shown yet hidden: the `hidden` attribute alone loses to the display:flex
  // rules above it (author CSS wins over the browser's own).
  return "#replay{box-sizing:border-box;margin:0;padding:0 16px;min-width:0}#replay *{box-sizing:border-box}"
         "#replay .replay-title{display:flex;align-items:center;justify-content:space-between;height:40px;margin:0}"
         "#replay h2{margin:0;height:40px;line-height:40px;overflow:hidden}"
         "#replay .replay-panels{display:flex;flex-wrap:wrap;gap:16px;align-items:flex-start;margin:0;padding:0}"
         "#replay .replay-panel{flex:0 0 auto;width:288px;margin:0;padding:0}"
         "#replay .replay-caption{height:40px;line-height:20px;font-size:13px;white-space:nowrap;overflow:hidden;"
         "text-overflow:ellipsis}"
         "#replay canvas,#replay .replay-reason{display:block;width:288px;height:288px;margin:0;border:0}"
         "#replay .replay-reason{background:#fbeeee;color:#a00;padding:1em;overflow:auto;white-space:normal}"
         "#replay .replay-controls{display:flex;flex-wrap:wrap;align-items:center;gap:.5em;margin:.8em 0}"
         "#replay .replay-slider{flex:1 1 12em}#replay .replay-clock{font-variant-numeric:tabular-nums}"
         "#replay .replay-notes{font-size:90%;color:#444}"
         "#replay.replay-theatre{position:fixed;top:0;left:0;right:0;bottom:0;z-index:1000;max-width:none;"
         "background:#fff;overflow:auto}"
         "#replay [hidden]{display:none!important}";
}

std::string replay_section(const SceneDescription& scene, const std::vector<EngineRun>& runs,
                           const std::vector<bool>& in_view) {
  const auto& m = *scene.mechanical;
  const size_t n = m.bodies.size();
  const long stride = body_stride(n);
  // Without JavaScript there is nothing to play: the panels (blank canvases), the controls and the
  // notes on them are `hidden` until replay.js shows them, and the one thing shown is the message,
  // first. (tabindex -1: a click in the replay gives it the focus, and with it the keys.)
  std::string html =
      "<section id=\"replay\" tabindex=\"-1\">\n"
      "<div class=\"replay-title\"><h2>Replay</h2><button type=\"button\" class=\"replay-close\" hidden>"
      "show the whole report</button></div>\n"
      "<noscript><p class=\"no\">The replay needs JavaScript.</p></noscript>\n<div class=\"replay-panels\" hidden>\n";
  for (size_t e = 0; e < runs.size(); ++e) {
    const EngineRun& r = runs[e];
    html += "<div class=\"replay-panel\"><div class=\"replay-caption\"><b>" + html_escape(r.engine) + "</b> <small>" +
            html_escape(r.version) + "</small>";
    // (a run that blew up, left out of the view the others share: its bodies leave its panel)
    if (r.supported && !r.frames.empty() && !in_view[e]) html += " <small class=\"replay-outside\">(goes out of view)</small>";
    html += "<br>";
    if (r.supported && !r.frames.empty()) {
      html += "<span class=\"replay-time\"></span> &nbsp; <span class=\"replay-energy\"></span></div>"
              "<canvas class=\"replay-canvas\" width=\"288\" height=\"288\" role=\"img\" aria-label=\"" +
              html_escape(r.engine) + " at the frame shown\"></canvas></div>\n";
    } else {
      html += "not run</div><div class=\"replay-reason\">";
      if (!r.supported)
        for (const auto& u : r.unsupported) html += html_escape(u) + "<br>";
      else
        html += "no frames were kept for this engine";
      html += "</div></div>\n";
    }
  }
  // The step buttons show glyphs, named for a screen reader by aria-label; the play button's name
  // is its text, which the script turns into "pause" while playing. The slider's aria-valuetext
  // (the time and the frame) is kept by the script.
  html += "</div>\n<div class=\"replay-controls\" hidden>"
          "<button type=\"button\" class=\"replay-back\" title=\"one frame back (&larr;)\" aria-label=\"one frame back\" "
          "aria-keyshortcuts=\"ArrowLeft\">&#9664;&#9646;</button>"
          "<button type=\"button\" class=\"replay-play\" title=\"play or pause (space)\" aria-keyshortcuts=\"Space\">"
          "play</button>"
          "<button type=\"button\" class=\"replay-forward\" title=\"one frame forward (&rarr;)\" "
          "aria-label=\"one frame forward\" aria-keyshortcuts=\"ArrowRight\">&#9646;&#9654;</button>"
          "<input type=\"range\" class=\"replay-slider\" min=\"0\" max=\"0\" value=\"0\" step=\"1\" aria-label=\"frame\">"
          "<select class=\"replay-speed\" aria-label=\"speed\"><option value=\"0.25\">0.25&times;</option>"
          "<option value=\"0.5\">0.5&times;</option><option value=\"1\" selected>1&times;</option>"
          "<option value=\"2\">2&times;</option><option value=\"4\">4&times;</option></select>"
          "<span class=\"replay-clock\"></span></div>\n<p class=\"replay-notes\" hidden>";
  std::string notes;
  if (const EngineRun* r = longest_run(runs); r && r->frames.size() >= 2)
    notes += fmt::format("{} frames, {:g} s apart (the first and the last state included); ",
                         r->frames.size(), r->frames[1].t - r->frames[0].t);
  // (The change is partly the physics in a scene that loses energy by design; an engine whose
  // first frame has E₀ = 0 shows ΔE itself, in joules.)
  notes += std::string("the same view for every engine. Under each panel, the time and the energy ") +
           (conserves_energy(scene) ? "error" : "change (this scene loses energy by design)") +
           " ΔE/E₀ = (E − E₀)/|E₀| of that frame (E₀: the energy of the first frame; where E₀ = 0, ΔE = E − E₀ in "
           "joules). ";
  if (m.dimensions == 3) notes += "A 3-D scene, seen along −z: x to the right, y up, nearer balls drawn over farther ones. ";
  if (m.dimensions == 1) {
    notes += "A 1-D scene: the bodies on a horizontal line, x to the right";
    notes += m.forces.pendulums.empty() ? ". " : " (a pendulum's coordinate is its angle θ, rad). ";
  }
  if (stride > 1)
    notes += fmt::format("Showing {} of the {} bodies (one in every {}), to keep the page fast. ",
                         (static_cast<long>(n) + stride - 1) / stride, n, stride);
  notes += "Keys, once the replay has the focus (click it, or tab to its controls): space plays or pauses, ← and → "
           "step one frame. <code>index.html?t=1.5</code> (or <code>#t=1.5</code>) "
           "opens the replay paused at the frame nearest t = 1.5 s; <code>?size=N</code> draws each panel N pixels wide.";
  html += notes + "</p>\n</section>\n"
                  "<script src=\"replay-data.js\"></script>\n<script src=\"replay.js\"></script>\n";
  return html;
}

}  // namespace motus::compare
