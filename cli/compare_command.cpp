#include "compare_command.hpp"

#include <fmt/format.h>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <future>
#include <new>
#include <sstream>

#include "motus/compare/backends/backend.hpp"
#include "cli_common.hpp"
#include "integrator_choice.hpp"
#include "locations.hpp"
#include "machine_load.hpp"
#include "option_values.hpp"
#include "output_files.hpp"
#include "plugin_loading.hpp"
#include "steps_and_times.hpp"
#include "motus/compare/comparison.hpp"
#include "motus/compare/explanations.hpp"
#include "draw_module.hpp"
#include "interrupt.hpp"
#include "motus/exact/exact_solution.hpp"
#include "motus/simulation.hpp"
#include "progress_bar.hpp"
#include "motus/compare/report.hpp"
#include "motus/scene_file/scene_file.hpp"
#include "motus/scene_file/spelling.hpp"

namespace fs = std::filesystem;

namespace motus::cli {
namespace {

// Without --render, the report still shows the scene (its first and last frames) and replays it:
// frames at up to 60 per second of simulated time, but no more than about two million
// coordinates over all engines (the ball gas gets a few dozen frames, a collision hundreds).
long replay_frame_every(const SceneDescription& scene, const compare::ComparisonOptions& options) {
  const double steps = static_cast<double>(fixed_step_count(options.duration, options.dt));
  const double coordinates = static_cast<double>(scene.mechanical->bodies.size()) * scene.mechanical->dimensions *
                             static_cast<double>(std::max<size_t>(options.engines.size(), 1));
  const double frames = std::clamp(std::min(60 * options.duration, 2e6 / std::max(coordinates, 1.0)), 2.0, 1500.0);
  return std::max(1L, static_cast<long>(std::ceil(steps / frames)));
}

std::string format_or_dash(const nlohmann::json& v, const char* format) {
  return v.is_null() ? std::string("-") : fmt::format(fmt::runtime(format), v.get<double>());
}

// A time per step as the report shows it (compare::microseconds_text).
std::string micros_or_dash(const nlohmann::json& v) {
  return v.is_null() ? std::string("-") : compare::microseconds_text(v.get<double>());
}

}  // namespace

CLI::App* add_compare_command(CLI::App& app, CompareOptions& o) {
  auto* c = app.add_subcommand("compare",
                               "Run one scene in motus, Box2D 2.4 and Bullet 3 with the same dt and the same metrics; "
                               "print the table and write a report folder (metrics CSV/JSON, plots, index.html)");
  c->add_option("scene", o.scene, "Scene file, or the name of a shipped scene (see `motus list`)")->required();
  add_list_option(c, "--engines", o.engines,
                  "Comma-separated engines: motus, box2d, bullet, and a loaded plug-in's name (default: motus, the "
                  "plug-in, box2d, bullet)");
  add_plugin_option(c, o.plugins);
  c->add_option("--integrator", o.integrator, "motus's integrator (default: the scene's); the peers integrate their own way");
  c->add_option("--dt", o.dt, "Step size, s (default: the scene's)")->transform(a_number());
  c->add_option("--duration", o.duration, "Time to run, s (default: the scene's)")->transform(a_number());
  c->add_option("--set", o.sets, "Override a scene field (repeatable), e.g. --set lattice.count=10000")->type_name("PATH=VALUE");
  c->add_option("--out", o.out, "Report folder (default: a new folder under runs/); must not exist yet")->check(folder_path());
  c->add_option("--samples", o.samples, "Metric samples over the run")->transform(whole_number_in(2, 100000))->capture_default_str();
  c->add_option("--repeats", o.repeats,
                "Timing rounds: every engine runs the scene again this many times, taking turns; the time per step "
                "is the fastest round's CPU time, with the median and the spread beside it (default: 5, or as many "
                "as fit in about 3 s when one round takes longer)")
      ->transform(whole_number_in(1, 100));
  c->add_flag("--json", o.json, "Print the summary as one JSON object instead of the table");
  CLI::Option* render = c->add_flag("--render", o.render,
              "Also draw the same instants of every engine side by side: PNG frames, an MP4 (ffmpeg) and a contact "
              "sheet, embedded in the report");
  c->add_option("--size", o.size, "The size of each engine's panel in the pictures (the report's first and last frames; every frame with --render)")->capture_default_str()->type_name("WxH");
  // (Without --render no frame is drawn: an --fps alone would be ignored without a word.)
  c->add_option("--fps", o.fps, "With --render: frames per second of simulated time")->capture_default_str()->needs(render);
  return c;
}

int compare_command(const CompareOptions& o) {
  const std::string path = resolve_scene_path(o.scene);
  const SceneDescription scene = load_scene(path, o.sets);
  if (!scene.mechanical)
    throw InputError(path + ": is a first-order system (\"" + scene.first_order->type +
                     "\"); compare runs scenes of bodies, which the peer engines model");

  load_plugins(o.plugins, o.json);

  compare::ComparisonOptions options;
  // A plug-in is a column of its own: motus's world with the plug-in's parts.
  const std::string plugin = plugins().empty() ? "" : plugins().parts_owner();
  auto known = compare::backend_names();
  if (!plugin.empty()) known.insert(known.begin() + 1, plugin);
  options.engines.clear();
  for (const auto& e : o.engines.empty() ? known : o.engines) {
    if (std::find(known.begin(), known.end(), e) == known.end())
      throw InputError("--engines: " + unknown_one_of("engine", e, known) +
                       (plugins().empty() && !closest_known(e, known) ? "; a plug-in's column needs --plugin FILE.so" : ""));
    // (Named twice, an engine would be one column, without a word about the other.)
    if (std::find(options.engines.begin(), options.engines.end(), e) != options.engines.end())
      throw InputError("--engines: \"" + e + "\" is named twice");
    options.engines.push_back(e);
  }
  // --integrator PLUGIN:NAME runs the plug-in's NAME in its column, and motus's own NAME (when
  // motus has one) in motus's; any other integrator runs in both.
  const Method requested = method_for(path, scene, o.integrator);
  options.method = requested;
  if (requested.is_external()) {
    const std::string own = requested.name().substr(requested.name().find(':') + 1);
    const auto builtin = integrator_from_name(own);
    options.method = builtin ? Method(*builtin) : method_for(path, scene, std::nullopt);
  }
  // A plug-in of integrators only, with none of them asked for, would have a column of motus's
  // own code under its name.
  const bool plugin_column = !plugin.empty() && std::find(options.engines.begin(), options.engines.end(), plugin) !=
                                                    options.engines.end();
  if (plugin_column && !plugins().parts().collisions && !plugins().parts().constraints && !requested.is_external()) {
    std::string names;
    for (const auto& m : plugins().integrators()) names += (names.empty() ? "" : ", ") + m.name();
    throw InputError("--plugin: " + plugin + " brings integrators only (" + names +
                     "): choose the one its column runs with --integrator " + plugin + ":NAME");
  }
  if (!plugin.empty()) {
    compare::PluginEngine engine;
    engine.name = plugin;
    for (const auto& p : plugins().plugins())
      if (p.name == plugin) engine.version = p.name + " plug-in (" + p.file + ")";
    engine.parts = plugins().parts();
    if (requested.is_external()) engine.method = requested;
    options.plugin = engine;
  }
  const std::string integrator_name =
      requested.is_external() ? options.method.name() + " (" + requested.name() + " in " + plugin + ")" : requested.name();
  options.dt = o.dt.value_or(scene.dt);
  options.duration = o.duration.value_or(scene.duration);
  if (!(options.dt > 0) || !std::isfinite(options.dt)) throw InputError("--dt: must be a finite number > 0");
  if (!(options.duration > 0) || !std::isfinite(options.duration)) throw InputError("--duration: must be a finite number > 0");
  options.samples = o.samples;
  options.repeats = o.repeats;
  // A plug-in's prints come once, with the metrics run; the timing rounds' go to /dev/null. The
  // machine's load is taken as the rounds begin and end (on a busy one the ratios may be off).
  QuietStandardOutput quiet;
  compare::MachineLoad load;
  load.cores = online_cores();
  const bool quieten = !plugins().empty();
  options.timing_rounds = [&quiet, &load, quieten](bool begin) {
    if (begin) {
      load.at_start = load_average();
      if (quieten) quiet.begin();
    } else {
      if (quieten) quiet.end();
      load.at_end = load_average();
    }
  };
  const std::string what = o.duration ? "--duration" : o.dt ? "--dt" : path + ": dt/duration";
  checked_step_count(options.duration, options.dt, what);
  check_time_resolution(scene.start_time, options.duration, options.dt, path + ": start_time", what);
  check_position_resolution(scene, options.dt, path, o.dt ? "--dt" : path + ": dt");
  int panel_width = 0, panel_height = 0;
  {
    char x = 0;
    std::istringstream size(o.size);
    if (!(size >> panel_width >> x >> panel_height) || x != 'x' || size.peek() != std::char_traits<char>::eof() ||
        panel_width < 64 || panel_height < 48 || panel_width > 4096 || panel_height > 4096)
      throw InputError("--size: must be WxH with 64 <= W <= 4096 and 48 <= H <= 4096 (got \"" + o.size + "\")");
  }
  // (Checked with or without --render: a value that is wrong is wrong either way.)
  if (!(o.fps > 0) || !std::isfinite(o.fps) || o.fps > 10000) throw InputError("--fps: must be a number > 0 (and at most 10000)");
  if (o.render && o.fps * options.duration < 1)
    throw InputError(fmt::format("--fps: {:g} frames per second of a {:g} s run is less than one frame after the first "
                                 "(a video needs two)", o.fps, options.duration));
  if (o.render) {
    options.frame_every = std::max(1L, std::lround(1 / (o.fps * options.dt)));
  } else {
    options.frame_every = replay_frame_every(scene, options);
  }
  // The frames (each engine's) and motus's samples (the others' reference) are kept until the report:
  // refused up front past 4 GB (a million balls with 100,000 samples grew by 30 MB a second, and
  // --render at 60 fps over 10⁵ s to std::bad_alloc).
  {
    const double numbers = 2.0 * scene.mechanical->dimensions * static_cast<double>(scene.mechanical->bodies.size());
    const double steps = static_cast<double>(fixed_step_count(options.duration, options.dt));
    const double frames = steps / static_cast<double>(options.frame_every) + 1;
    const double engines = static_cast<double>(std::max<size_t>(options.engines.size(), 1));
    // (With --render, each engine's frames and the drawing's copy of them. motus's samples: every step
    // of a run with fewer steps than --samples.)
    const double samples = std::min(static_cast<double>(options.samples), steps);
    const double kept = engines * frames * (o.render ? 2 : 1) + samples + 1;
    const double gigabytes = kept * (numbers * 8 + 48) / 1e9;
    if (gigabytes > 4)
      throw InputError(fmt::format("{}: keeps about {:.0f} GB of states for the report ({:.0f} frames of {} engine{} and "
                                   "{:.0f} samples, {:.0f} numbers each; at most 4 GB): fewer --samples, {}a shorter --duration",
                                   o.render ? "--fps/--samples/--duration" : "--samples/--duration", gigabytes, frames,
                                   options.engines.size(), options.engines.size() == 1 ? "" : "s", samples,
                                   numbers, o.render ? "a lower --fps, " : ""));
  }
  const auto among_engines = [&](const std::string& engine) {
    return std::find(options.engines.begin(), options.engines.end(), engine) != options.engines.end();
  };
  const bool motus_runs = among_engines("motus");
  // Fail before any engine runs if motus cannot run this scene with this integrator.
  if (motus_runs) Simulation check(scene, options.method);
  if (options.plugin && among_engines(plugin)) {
    Simulation check(scene, options.plugin->method.value_or(options.method), options.plugin->parts);
    // A plug-in of which its column uses nothing (collision rules on kepler) says so, on standard
    // error (--json's object is standard output's): the column is motus's own code under its name.
    for (const auto& note : unused_plugin_notes(scene.name, check.method(), check.world())) tell("{}\n", note);
  } else {
    for (const auto& p : plugins().plugins())
      tell("note: the plug-in {} brings {}, and --engines leaves out its column ({}): it is not used in this run\n",
           p.file, what_plugin_brings(p), plugin);
  }

  // A scene that starts overlapping is moved apart before the first step (docs/scene-format.md,
  // "Overlap"): said on standard error (--json's object is standard output's), and in the report.
  const compare::InitialOverlap overlap =
      scene.mechanical ? compare::initial_overlap(*scene.mechanical) : compare::InitialOverlap{};
  if (const std::string start = compare::initial_overlap_note(overlap, true); !start.empty())
    tell("note: {}: {}\n", path, start);

  const bool default_folder = o.out.empty();
  const std::string folder = default_folder ? default_run_folder("compare", scene.name) : o.out;
  if (!default_folder && output_exists(folder)) throw InputError(folder + ": already exists; compare never overwrites a report (choose another --out)");
  // The report is written into a folder beside the final one and renamed when it is whole:
  // a run that fails or is interrupted leaves no folder that looks complete. Made now, so a
  // folder that cannot be made is refused before any engine runs.
  PartialFolder partial(folder, default_folder);
  const std::string work = partial.path();

  ProgressBar progress(0, 1, "compare " + scene.name, 1);
  progress.phase("stepping the engines", 0, 1);
  const auto runs = compare::run_comparison(scene, options, [&](double f) { progress.update(f); });

  compare::ReportContext context;
  context.initial_overlap = overlap;
  context.scene_name = scene.name;
  context.scene_file = path;
  context.description = scene.description;
  context.integrator = integrator_name;
  context.method = options.method.name();
  context.scene = &scene;
  context.dt = options.dt;
  context.duration = options.duration;
  context.samples = options.samples;
  context.dimensions = scene.mechanical->dimensions;
  context.bodies = static_cast<long>(scene.mechanical->bodies.size());
  // The rounds run (the default's number is decided by how long the metrics runs took).
  for (const auto& run : runs)
    if (run.supported) {
      context.repeats = std::max(context.repeats, static_cast<int>(run.round_seconds.size()));
      context.samples = static_cast<long>(run.rows.size()) - 1;  // (as many as were taken: the start is no sample)
    }
  const auto conserved = compare::conserved_quantities(scene);
  context.momentum_conserved = conserved.momentum;
  context.angular_momentum_conserved = conserved.angular_momentum;
  // The plots are gnuplot's, a program of its own: drawn while the pictures are (OSMesa, here), a
  // small compare's wall time is the longer of the two rather than their sum (on two cores, 0.1 s
  // of its 0.5). The plotting thread gets its own copy of the context, since the pictures' block
  // below writes the picture fields of this one.
  std::future<std::string> plots =
      std::async(std::launch::async, [&work, &runs, c = context] { return compare::draw_figures(work, c, runs); });
  std::string picture_warning;
  {  // --render: every frame, a video and a contact sheet; otherwise the first and the last frame
    draw::ComparisonJob job;
    job.first_and_last_only = !o.render;
    job.scene = &scene;
    job.width = panel_width;
    job.height = panel_height;
    job.fps = 1 / (static_cast<double>(options.frame_every) * options.dt);
    job.folder = work;
    size_t frames = 0;
    for (const auto& run : runs) frames = std::max(frames, run.frames.size());
    progress.phase("drawing", 0, static_cast<double>(o.render ? frames : 2));
    job.progress = [&](long done, long total) {
      progress.update(static_cast<double>(o.render ? done : done == 1 ? 1 : 2));
      // After the last frame the drawing module makes the contact sheet and the video (ffmpeg):
      // seconds (9.5 for ball_gas) in which the bar stood at "drawing 100 %".
      if (o.render && done == total) progress.note("making the contact sheet and the video");
    };
    for (const auto& run : runs) {
      draw::Panel panel{run.engine, run.version, {}, run.unsupported};
      for (size_t k = 0; k < run.frames.size(); ++k) {
        const compare::Snapshot& s = run.frames[k];
        panel.frames.times.push_back(s.t);
        std::vector<double> state(s.x);
        state.insert(state.end(), s.v.begin(), s.v.end());
        panel.frames.states.push_back(std::move(state));
        panel.frames.energies.push_back(run.frame_energies[k]);
      }
      job.panels.push_back(std::move(panel));
    }
    draw::ComparisonPictures pictures;
    std::string error;
    try {
      error = draw_module().draw_comparison(job, pictures);
    } catch (const InputError& e) {  // no drawing module: the report is still worth having
      error = e.what();
    }
    // Memory that ran out while drawing is a failed run (exit 1, saying so), not pictures skipped:
    // the report would lack what every report has, for a reason the user can do something about.
    if (draw::out_of_memory(error)) throw std::bad_alloc();
    // A picture that could not be written (a full disk) is a failed run: the report would link a
    // truncated PNG. Named where the report was to be (the partial folder goes with the failure).
    if (!error.empty() && pictures.write_failed) throw std::runtime_error(error);
    if (error.empty()) {
      context.first_and_last = pictures.first_and_last;
      context.video = pictures.video;
      context.contact_sheet = pictures.contact_sheet;
      picture_warning = pictures.warning;
    } else {
      picture_warning = "pictures skipped: " + error;
    }
    context.pictures_note = picture_warning;  // (the page says so too, not only the terminal)
  }
  const std::string warning = plots.get();
  progress.note("writing the report");
  context.load = load;
  compare::write_report(work, context, runs, warning);
  progress.finish();
  stop_if_interrupted();  // (a plot that died of the same Ctrl-C is no reason to finish the report)
  const std::string written = partial.complete();  // (a default folder's name may have taken a number)
  nlohmann::json summary = compare::summary_json(context, runs);
  summary["report"] = written + "/index.html";

  if (o.json) {
    fmt::print(data_output(), "{}\n", summary.dump(2, ' ', false, nlohmann::json::error_handler_t::replace));  // (a path not in UTF-8)
  } else {
    const long steps = fixed_step_count(options.duration, options.dt);
    // (The run ends after whole steps: kepler's 2π s at 0.01 s ends at 6.29 s, as motus run says.)
    const auto end = compare::end_past_duration(scene.start_time, options.duration, options.dt);
    // (motus's integrator only where motus ran: --engines box2d,bullet named one that did nothing.)
    fmt::print("{}: {} {}, {}-D, dt = {:g} s, {:g} s ({} step{}{}){}\n", scene.name, context.bodies,
               context.bodies == 1 ? "body" : "bodies", context.dimensions, options.dt, options.duration, steps,
               steps == 1 ? "" : "s", end ? fmt::format(", ending at t = {:g} s", *end) : "",
               motus_runs ? "; motus integrator " + integrator_name : std::string());
    // Where the scene has an exact answer, the distance from it matters more than from motus.
    const bool exact_known = has_exact_solution(scene);
    const char* distance_key = exact_known ? "max_distance_from_exact" : "max_distance_from_motus";
    // What the timing line says is what was done: no round, one, or several; turns only between engines.
    const long timed = std::count_if(runs.begin(), runs.end(), [](const compare::EngineRun& r) { return r.supported; });
    if (context.repeats == 0)
      fmt::print("us/step: nothing was timed (no engine could run the scene)\n");
    else if (context.repeats == 1)
      fmt::print("us/step: CPU time per step in one timing round{}; with one round the median is that round and there "
                 "is no spread\n",
                 timed > 1 ? ", the engines one after another" : "");
    else
      fmt::print("us/step: CPU time per step, the fastest of {} rounds{}, the median beside it; "
                 "spread = (slowest - fastest) / fastest\n",
                 context.repeats, timed > 1 ? " (engines taking turns)" : "");
    if (context.repeats > 0 && compare::busy_machine(load)) fmt::print("warning: {}\n", compare::busy_machine_warning(load));
    fmt::print("\n");
    const bool joules = summary["energy_unit"] == "J";
    // The momentum column: a pendulum's is m·θ'; marked "*", with a note under the table, where
    // it is not an engine's error (the report's decision: conserved_quantities, momentum_footnote).
    const bool angle = summary["momentum_quantity"] != "momentum", change = summary["momentum_unit"] != "scale";
    const std::string momentum_footnote = compare::momentum_footnote(scene, context.momentum_conserved);
    const std::string momentum_heading =
        std::string(angle ? (change ? "m theta' [kg rad/s]" : "m theta'") : (change ? "p [kg m/s]" : "momentum")) +
        (momentum_footnote.empty() ? "" : "*");
    const int momentum_width = std::max(13, static_cast<int>(momentum_heading.size()) + 2);
    fmt::print("{:<8}{:>13}{:>13}{:>{}}{:>13}{:>13}{:>13}{:>11}{:>11}{:>8}{:>12}\n", "engine",
               joules ? "E drift [J]" : "energy drift", joules ? "max |dE| [J]" : "max |dE|/E0",
               momentum_heading, momentum_width,
               "penetration", "constraint", exact_known ? "from exact" : "from motus",
               "us/step", "median", "spread", "time/motus");
    for (const auto& e : summary["engines"]) {
      if (!e["supported"].get<bool>()) {
        for (const auto& u : e["unsupported"]) fmt::print("{:<8}{}\n", e["engine"].get<std::string>(), u.get<std::string>());
        continue;
      }
      fmt::print("{:<8}{:>13}{:>13}{:>{}}{:>13}{:>13}{:>13}{:>11}{:>11}{:>8}{:>12}\n", e["engine"].get<std::string>(),
                 format_or_dash(e["energy_drift"], "{:+.2e}"), format_or_dash(e["max_energy_error"], "{:.2e}"),
                 format_or_dash(e["momentum_drift"], "{:.2e}"), momentum_width,
                 format_or_dash(e["max_penetration"], "{:.2e}"),
                 format_or_dash(e["constraint_error"], "{:.2e}"), format_or_dash(e[distance_key], "{:.2e}"),
                 micros_or_dash(e["us_per_step"]), micros_or_dash(e["us_per_step_median"]),
                 e["us_per_step_spread"].is_null()
                     ? std::string("-")
                     : fmt::format("{:.0f}%", 100 * e["us_per_step_spread"].get<double>()),
                 format_or_dash(e["time_relative_to_motus"], "{:.2f}x"));
    }
    if (!momentum_footnote.empty()) fmt::print("{}\n", momentum_footnote);
    for (const auto& e : summary["engines"])
      for (const auto& n : e["notes"]) fmt::print("note ({}): {}\n", e["engine"].get<std::string>(), n.get<std::string>());
    for (const auto& e : summary["engines"])
      if (e.contains("not_finite_from") && !e["not_finite_from"].is_null())
        fmt::print("note ({}): blew up: its energy is not finite from t = {:g} s on\n",
                   e["engine"].get<std::string>(), e["not_finite_from"].get<double>());
    if (summary.contains("notice")) fmt::print("\n{}\n", summary["notice"].get<std::string>());
    fmt::print("\nreport: {} (what each column means, the plots{})\n", summary["report"].get<std::string>(),
               summary.contains("exact") ? ", the exact answer" : "");
  }
  if (!warning.empty()) tell("motus: {}\n", warning);
  if (!picture_warning.empty()) tell("motus: {}\n", picture_warning);
  return 0;
}

}  // namespace motus::cli
