#include "render_command.hpp"

#include <fmt/format.h>

#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <filesystem>
#include <new>
#include <fstream>
#include <regex>

#include <fcntl.h>
#include <stdlib.h>  // mkdtemp
#include <sys/file.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>

#include "cli_common.hpp"
#include "integrator_choice.hpp"
#include "locations.hpp"
#include "option_values.hpp"
#include "output_files.hpp"
#include "plugin_loading.hpp"
#include "steps_and_times.hpp"
#include "draw_module.hpp"
#include "interrupt.hpp"
#include "motus/process/run_program.hpp"
#include "motus/scene_error.hpp"
#include "motus/simulation.hpp"
#include "progress_bar.hpp"
#include "motus/scene_file/scene_file.hpp"

namespace fs = std::filesystem;

namespace motus::cli {
namespace {

std::pair<int, int> parse_size(const std::string& text) {
  // (Nine digits at most, so that stoi cannot overflow; a side past what OSMesa draws is said as
  // that by the canvas, not as a WIDTHxHEIGHT written wrong.)
  static const std::regex pattern(R"((\d{1,9})[xX](\d{1,9}))");
  std::smatch m;
  if (!std::regex_match(text, m, pattern)) throw InputError("--size: expected WIDTHxHEIGHT, e.g. 640x480 (got \"" + text + "\")");
  const int w = std::stoi(m[1]), h = std::stoi(m[2]);
  if (w < 16 || h < 16) throw InputError("--size: each side must be at least 16 pixels (got " + text + ")");
  return {w, h};
}

// What a render wrote into its folder, one file name a line: all that --overwrite replaces
// (never a file of the user's that happens to be there).
constexpr const char* kManifest = ".motus-render";

// With --trails, the states a body's trail goes through between two frames, at most: every step
// at a scene's usual dt (a few steps a frame), and no more than this for a small dt.
constexpr double kTrailPointsPerFrame = 16;

// Frames per second of video when --fps is not given.
constexpr double kDefaultFps = 30;

// Without --speed a simulated second (year) takes a second to watch, unless the run is longer than
// this many seconds of video: then it plays faster, in this long. thomas's 500 s at 1:1 drew 10,001
// frames (393 MB, two and a half minutes) for an eight-minute video of a curve that grows slowly.
constexpr double kLongestDefaultVideo = 20;

double playing_speed(const std::optional<double>& speed, double duration) {
  if (speed) return *speed;
  return duration > kLongestDefaultVideo ? duration / kLongestDefaultVideo : 1;
}

// The frame rate a render draws at, per simulated second: --fps, else kDefaultFps a second of
// video at the playing speed, but never more than one frame a step of a fixed-step integrator.
// Frames between two steps show the state of the step after them, the one the frame before
// showed: World2 (dt = 0.2 years) drew 6001 frames at 30 a year, of which 1001 differ (316 MB and a
// minute, for the same video). At exactly 1/dt the frames' times are the steps' (the step clock of
// Simulation::advance lands on t0 + k·dt), so every frame is a new step. An adaptive integrator
// lands on every frame's time: any rate is new states.
double frame_rate(const std::optional<double>& fps, double speed, const SceneDescription& scene, const Method& method) {
  if (fps) return *fps;
  const double rate = kDefaultFps / speed;
  return !method.adaptive() && scene.dt * rate > 1 ? 1 / scene.dt : rate;
}

// The names an earlier render listed in FOLDER/.motus-render (only plain names: no folder, no
// hidden file).
std::vector<std::string> listed_names(const fs::path& folder) {
  std::vector<std::string> names;
  std::ifstream manifest(folder / kManifest);
  for (std::string name; std::getline(manifest, name);)
    if (!name.empty() && name.find('/') == std::string::npos && name[0] != '.') names.push_back(name);
  return names;
}

// The files a render writes into its folder: its frames, then its video.
std::vector<std::string> render_names(long frames, const std::string& video_name) {
  std::vector<std::string> names;
  for (long k = 0; k < frames; ++k) names.push_back(fmt::format("frame_{:05d}.png", k));
  if (!video_name.empty()) names.push_back(video_name);
  return names;
}

// The output folder, checked before anything is drawn: it must not exist, or (--overwrite) every
// file this render will write must be one an earlier render wrote there — a frame_00003.png or a
// video of the user's that happens to have the name is refused (it was replaced, then removed when
// the render failed), as is a link or anything but a regular file (writing it would write where
// the link leads, outside the folder). Nothing is removed here: see RenderInProgress.
void check_folder(const std::string& out, bool overwrite, const std::vector<std::string>& names) {
  // (Looked at without throwing: a loop of links was "the run failed: filesystem error", exit 1. "f/"
  // is f: a file there "could not be created (File exists)".)
  const std::string folder = without_trailing_separators(out).string();
  if (!output_exists(folder)) return;
  const auto status = looked_at(folder, "--out");
  if (!fs::exists(status)) throw InputError(out + ": is a link to nothing; choose another --out");
  if (!fs::is_directory(status)) throw InputError(out + ": exists and is not a folder; choose another --out");
  if (!overwrite) throw InputError(out + ": already exists; choose another --out or pass --overwrite");
  const std::vector<std::string> ours = listed_names(out);
  for (const auto& name : names) {
    std::error_code ignored;
    const fs::path file = fs::path(out) / name;
    const auto status = fs::symlink_status(file, ignored);
    if (!fs::exists(status)) continue;
    if (!fs::is_regular_file(status))
      throw InputError(file.string() + ": is " + (fs::is_symlink(status) ? "a link" : "not a regular file") +
                       "; a render writes no file through it (remove it or choose another --out)");
    if (std::find(ours.begin(), ours.end(), name) == ours.end())
      throw InputError(file.string() + ": is not a file an earlier render wrote here (" + kManifest +
                       " does not list it); --overwrite replaces only those (remove it or choose another --out)");
  }
}

// A render is drawn into a folder of its own inside --out (.motus-render-partial-XXXXXX) and moved
// into place only when it is whole: a render that fails or is stopped (a full disk, a video ffmpeg
// cannot make, Ctrl-C) leaves --out as it found it — an earlier render in it included — and removes
// --out itself if it made it.
class RenderInProgress {
public:
  // (out "frames/" is the folder frames: made as its own parent's child, it was made, then found
  // "already there", exit 2, and left behind)
  RenderInProgress(const std::string& out, bool make_folder) : out_(without_trailing_separators(out).string()) {
    std::error_code error;
    if (make_folder) {
      // Made here or refused: another render started beside this one may have made it since it was
      // looked at (both went on, and the second replaced the first's frames without --overwrite).
      const fs::path parent = fs::path(out_).parent_path();
      made_folders_ = folders_not_there_yet(out_);  // (they go again with it, when still empty)
      if (!parent.empty()) fs::create_directories(parent, error);
      if (!error && !fs::create_directory(out_, error) && !error)
        throw InputError(out_ + ": already exists (made meanwhile, by another run?); choose another --out or pass --overwrite");
    }
    if (error) throw InputError(out_ + ": cannot be created (" + why_not_created(out_, error) + ")");
    // One render at a time in a folder: two at once moved their frames in turn into it, a mix of both.
    lock_ = ::open(out_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (lock_ < 0 || ::flock(lock_, LOCK_EX | LOCK_NB) != 0) {
      const int e = errno;
      if (lock_ >= 0) ::close(lock_);
      throw InputError(out_ + (e == EWOULDBLOCK ? ": another motus render is writing into it; wait for it or choose another --out"
                                                : ": cannot be opened (" + std::string(std::strerror(e)) + ")"));
    }
    std::string name = (fs::path(out_) / ".motus-render-partial-XXXXXX").string();
    if (::mkdtemp(name.data()) == nullptr) {
      const int e = errno;
      ::close(lock_);
      remove_if_empty(made_folders_);
      throw InputError(out_ + ": cannot be written in (" + std::strerror(e) + ")");
    }
    partial_ = name;
    say_as_final(partial_, out_);  // (a frame that cannot be written is named where it was to be)
  }
  RenderInProgress(const RenderInProgress&) = delete;
  RenderInProgress& operator=(const RenderInProgress&) = delete;
  ~RenderInProgress() {
    if (!moved_) {
      std::error_code ignored;
      fs::remove_all(partial_, ignored);  // (a folder of motus's own making)
      // --out itself when this render made it (and has held its lock since): a failure after the frames
      // were moved in (writing the list of them, on a full disk) left a finished-looking render there.
      if (!made_folders_.empty()) fs::remove_all(out_, ignored);
      remove_if_empty(made_folders_);
    }
    ::close(lock_);  // (and the lock with it)
  }
  const std::string& folder() const { return partial_; }

  // Into place: NAMES over the earlier render's files of the same names (a rename replaces each at
  // once), then the earlier render's other files removed, and the list of what is there now. The
  // list names both renders' files until the last step, so that nothing motus wrote is ever unlisted.
  void move_into_place(const std::vector<std::string>& names) {
    const fs::path out = out_;
    std::vector<std::string> earlier = listed_names(out), both = earlier;
    for (const auto& n : names)
      if (std::find(both.begin(), both.end(), n) == both.end()) both.push_back(n);
    write_list(both);
    for (const auto& n : names) {
      std::error_code error;
      fs::rename(fs::path(partial_) / n, out / n, error);
      if (error) throw std::runtime_error((out / n).string() + ": could not be written (" + error.message() + ")");
    }
    for (const auto& n : earlier)
      if (std::find(names.begin(), names.end(), n) == names.end()) {
        std::error_code ignored;
        if (fs::is_regular_file(fs::symlink_status(out / n, ignored))) fs::remove(out / n, ignored);
      }
    write_list(names);
    moved_ = true;
    std::error_code ignored;
    fs::remove_all(partial_, ignored);
  }

private:
  // FOLDER/.motus-render, written whole beside the frames and moved over the old one.
  void write_list(const std::vector<std::string>& names) const {
    const fs::path list = fs::path(partial_) / kManifest;
    {
      std::ofstream file(list, std::ios::trunc);
      for (const auto& n : names) file << n << '\n';
      file.flush();
      if (!file) throw std::runtime_error((fs::path(out_) / kManifest).string() + ": could not be written (" +
                                          std::strerror(errno) + ")");
    }
    std::error_code error;
    fs::rename(list, fs::path(out_) / kManifest, error);
    if (error)
      throw std::runtime_error((fs::path(out_) / kManifest).string() + ": could not be written (" + error.message() + ")");
  }

  std::string out_, partial_;
  // --out and the folders above it this render made, deepest first (none: --out was there already).
  std::vector<std::string> made_folders_;
  int lock_ = -1;  // the folder, open: flock'ed while this render writes into it
  bool moved_ = false;
};

}  // namespace

CLI::App* add_render_command(CLI::App& app, RenderOptions& o) {
  auto* render = app.add_subcommand("render", "Simulate a scene and draw it as PNG frames (and optionally one MP4 or GIF)");
  render->add_option("scene", o.scene, "Scene file, or the name of a shipped scene (see `motus list`)")->required();
  render->add_option("--out", o.out, "Folder for frame_00000.png, ... (must not exist unless --overwrite)")->required()->check(folder_path());
  render->add_option("--size", o.size, "Frame size in pixels")->type_name("WxH")->capture_default_str();
  render->add_option("--fps", o.fps,
                     "Frames per second of simulated time (World2: per simulated year) (default: 30 a second of "
                     "video at --speed, but at most one a step)");
  render->add_option("--speed", o.speed,
                     "Simulated seconds (World2: years) a second of video plays (default: 1, or for a run longer "
                     "than 20 s, as many as play it in 20 s)")
      ->transform(a_number());
  render->add_option("--duration", o.duration, "Simulated time to draw, s (World2: years; default: the scene's)")->transform(a_number());
  render->add_option("--integrator", o.integrator, "Integrator (default: the scene's); see `motus list`");
  render->add_option("--set", o.sets, "Override a scene field, e.g. --set lattice.count=1000 (repeatable)")
      ->type_name("PATH=VALUE");
  render->add_option("--video", o.video, "Also assemble the frames into SCENE.mp4 or SCENE.gif with ffmpeg")
      ->check(CLI::IsMember({"mp4", "gif"}));
  render->add_flag("--overwrite", o.overwrite, "Reuse an existing --out folder (the frames and video an earlier render wrote there are replaced; nothing else is touched)");
  render->add_flag("--trails", o.trails, fmt::format("Draw each body's recent path (scenes with at most {} bodies)", draw::RenderJob::kMostTrailedBodies));
  render->add_flag("--arrows", o.arrows, "Draw velocity arrows (where each body will be in 0.25 s)");
  add_plugin_option(render, o.plugins);
  render->add_option("--supersample", o.supersample, "Anti-aliasing: render N times larger and average (1-4)")
      ->transform(whole_number_in(1, 4))
      ->capture_default_str();
  return render;
}

int render_command(const RenderOptions& o) {
  const std::string path = resolve_scene_path(o.scene);
  SceneDescription scene = load_scene(path, o.sets);
  load_plugins(o.plugins);
  const Method method = method_for(path, scene, o.integrator);
  const std::string integrator_name = method.name();
  const auto [width, height] = parse_size(o.size);
  if (o.fps && (!(*o.fps > 0) || !std::isfinite(*o.fps) || *o.fps > 10000))
    throw InputError("--fps: must be a number > 0 (and at most 10000)");
  if (o.speed && (!(*o.speed > 0) || !std::isfinite(*o.speed)))
    throw InputError("--speed: must be a finite number > 0");
  const std::string unit = time_unit_of(scene);  // "s" or "years"
  const std::string one_unit = unit == "years" ? "year" : "second";  // ("per simulated year")
  const double duration = o.duration.value_or(scene.duration);
  if (!(duration >= 0) || !std::isfinite(duration)) throw InputError("--duration: must be a finite number >= 0");
  const double speed = playing_speed(o.speed, duration);
  const double fps = frame_rate(o.fps, speed, scene, method);
  const bool one_a_step = !o.fps && fps != kDefaultFps / speed;  // (said in the summary: why not 30 a second)
  // The video shows `speed` simulated seconds (years) a second: fps of them a simulated second.
  const double video_fps = fps * speed;
  const double frame_count = std::floor(duration * fps + 1e-9) + 1;  // (a double first: 1e18 s is no long)
  if (frame_count > 100000)
    throw InputError(fmt::format("--duration/--fps: {} frames is too many (at most 100,000)",
                                 frame_count < 1e15 ? fmt::format("{:.0f}", frame_count) : fmt::format("{:.3g}", frame_count)));
  const long frames = static_cast<long>(frame_count);
  // A video plays the frames at fps × speed, so that `speed` simulated seconds (years) take a second
  // to watch whatever the rate: the default's one frame a step plays as 30 a second with each step
  // repeated did. Checked before anything is drawn (ffmpeg would refuse it only after every frame had
  // been, and the failed run's folder goes with them). At one frame a step (no --fps) it is the
  // scene's step that is named, not an --fps the user did not give.
  if (!o.video.empty() && frames < 2)
    throw InputError(!one_a_step ? fmt::format("--fps: {:g} frames per second of a {:g} {} run is less than one frame "
                                               "after the first (a video needs two)", fps, duration, unit)
                                 : fmt::format("--duration: a video needs two frames, and a {:g} {} run at one frame a step "
                                               "(dt = {:g} {}) has one: a longer --duration, or a smaller --set dt=...",
                                               duration, unit, scene.dt, unit));
  // A GIF's frame delay is in hundredths of a second, and players slow a delay below 2 to 10: a
  // GIF past 50 frames a second played at 10 without a word (0.1 s of 10,000 a second took 100 s).
  // (Without --fps the rate is at most 30.)
  const std::string rate_options = o.speed ? "--fps/--speed" : "--fps";
  const std::string rate_product =
      speed == 1 ? "" : fmt::format(" ({:g} a simulated {} × {:g} {} a second)", fps, one_unit,
                                    speed, unit);
  if (o.video == "gif" && video_fps > 50)
    throw InputError(fmt::format("{}: a GIF plays at most 50 frames per second (its frame delay is in hundredths of a "
                                 "second), not {:g}{}: a lower {}, or --video mp4",
                                 rate_options, video_fps, rate_product, speed == 1 ? "--fps" : "--fps or --speed"));
  if (!o.video.empty() && video_fps < 0.001)
    throw InputError(!one_a_step ? fmt::format("{}: a video at {:g} frames per second{} is slower than ffmpeg plays "
                                               "(0.001 at the least)", rate_options, video_fps, rate_product)
                                 : fmt::format("--video: one frame a step (dt = {:g} {}) is {:g} frames per second{}, "
                                               "slower than ffmpeg plays (0.001 at the least): --fps 0.001 or more",
                                               scene.dt, unit, video_fps, rate_product));
  check_time_resolution(scene.start_time, duration, scene.dt, path + ": start_time",
                        o.duration ? "--duration" : path + ": dt/duration");
  check_position_resolution(scene, scene.dt, path, path + ": dt");
  const draw::Api& drawing = draw_module();
  if (!o.video.empty() && process::find_program("ffmpeg").empty())
    throw InputError("ffmpeg not found on PATH: --video needs it (install the Debian package ffmpeg)");
  // A canvas and a font, before any folder is made.
  if (const std::string error = drawing.check(width, height, o.supersample); !error.empty()) {
    if (draw::out_of_memory(error)) throw std::bad_alloc();  // (exit 1, out of memory: not a bad option)
    throw InputError(error);
  }

  std::optional<Simulation> built;
  try {
    built.emplace(scene, method, plugins().parts());
  } catch (const SceneError& e) {  // building the run (e.g. a symplectic integrator on a first-order system)
    throw InputError(path + ": " + (e.field().empty() ? "" : e.field() + ": ") + e.what());
  }
  Simulation& sim = *built;
  // Every state drawn from is kept until the drawing (a frame's for bodies; a first-order scene's
  // every step, its curve drawn through them): refused up front past 4 GB. A million balls at 60
  // frames a second, or lorenz for 9e5 s, grew to std::bad_alloc after a minute.
  {
    double states = frame_count;
    if (!scene.is_mechanical() && !method.adaptive()) {
      const double steps = static_cast<double>(fixed_step_count(duration, scene.dt));
      states += scene.output_interval > 0 ? std::min(steps, duration / scene.output_interval) : steps;
    }
    const double gigabytes = states * (static_cast<double>(sim.state().size()) * 8 + 32) / 1e9;
    if (gigabytes > 4)
      throw InputError(fmt::format("--duration/--fps: drawing this run keeps about {:.0f} GB of states ({:.0f} states of "
                                   "{} numbers; at most 4 GB): fewer frames (--fps), a shorter --duration{}",
                                   gigabytes, states, sim.state().size(),
                                   scene.is_mechanical() ? "" : ", or --set output_interval=S (a state every S s)"));
  }
  const std::string video_name = o.video.empty() ? "" : safe_file_name(scene.name) + "." + o.video;  // a name is not a path
  const bool made_folder = !output_exists(o.out) && !fs::exists(o.out);  // (a path not to be looked at: bad input)
  const std::vector<std::string> names = render_names(frames, video_name);
  check_folder(o.out, o.overwrite, names);
  RenderInProgress rendering(o.out, made_folder);
  // A plug-in of which this render uses nothing (cloth's projection on spring) says so, on standard
  // error, once nothing is left to refuse: its frames are motus's own code's.
  for (const auto& note : unused_plugin_notes(scene.name, method, sim.world())) tell("{}\n", note);

  // Simulate: mechanical scenes keep one state per frame; first-order ones every step
  // too (an attractor's curve is drawn through all of them), and so do bodies drawn with trails
  // (up to kTrailPointsPerFrame a frame): a trail through the frames alone cut across every bounce.
  const double t0 = sim.time(), dt = scene.dt;
  const Tolerance tolerance{scene.atol, scene.rtol};
  draw::Frames recording;
  draw::RenderJob job;
  auto record = [&](const Simulation& s) {
    recording.times.push_back(s.time());
    recording.states.emplace_back(s.state().data(), s.state().data() + s.state().size());
    if (const auto e = s.energy()) recording.energies.push_back(e->total);
  };
  const bool trails_drawn = o.trails && scene.is_mechanical() && scene.mechanical->bodies.size() <= draw::RenderJob::kMostTrailedBodies;
  const bool every_step = !scene.is_mechanical() || trails_drawn;
  const double min_gap = scene.is_mechanical()       ? 0.999 / (fps * kTrailPointsPerFrame)
                         : scene.output_interval > 0 ? scene.output_interval * 0.999
                                                     : 0;
  ProgressBar progress(0, static_cast<double>(frames), scene.name, 1);
  progress.phase("simulating", 0, static_cast<double>(frames));
  const auto began = std::chrono::steady_clock::now();
  record(sim);
  job.frame_index.push_back(0);
  for (long k = 1; k < frames; ++k) {
    const double target = t0 + static_cast<double>(k) / fps;
    if (sim.time() < target - 1e-9 * std::max(1.0, std::abs(target))) {
      sim.advance(target, dt, tolerance, [&](const Simulation& s) {
        if (every_step && s.time() - recording.times.back() >= min_gap) record(s);
      });
      if (!every_step || recording.times.back() != sim.time()) record(sim);
    }
    job.frame_index.push_back(recording.times.size() - 1);
    progress.update(static_cast<double>(k));
  }
  // Frames that show the state the frame before showed: only at an --fps above one frame a step (the
  // default never is). Said before the drawing, which takes the time, so that it can be stopped; not
  // an error (a video at a round rate may be wanted), and the summary counts them again.
  long distinct = frames > 0 ? 1 : 0;
  for (size_t k = 1; k < job.frame_index.size(); ++k) distinct += job.frame_index[k] != job.frame_index[k - 1];
  if (distinct < frames && !method.adaptive() && fps * scene.dt > 1) {
    progress.finish();  // (the bar's line cleared first, on a terminal)
    tell("motus: note: --fps {:g} is more than one frame a step of {} (dt = {:g} {}): {} of the {} frames differ, the "
         "others repeat the one before (--fps {:g} draws each step once)\n",
         fps, scene.name, scene.dt, unit, distinct, frames, 1 / scene.dt);
  }

  // When the run stopped being finite: read here, as the drawing takes the states.
  double not_finite_from = std::numeric_limits<double>::quiet_NaN();
  for (size_t k = 0; k < recording.states.size() && std::isnan(not_finite_from); ++k)
    if (!std::all_of(recording.states[k].begin(), recording.states[k].end(), [](double y) { return std::isfinite(y); }))
      not_finite_from = recording.times[k];

  // Draw.
  job.scene = &scene;
  job.frames = &recording;
  job.width = width;
  job.height = height;
  job.supersample = o.supersample;
  job.trails = o.trails;
  job.arrows = o.arrows;
  job.note = integrator_name;  // and the --set overrides, but the integrator only once
  // A plug-in's collisions or projection that ran are named, as motus run names them in its passes:
  // "verlet" alone read as motus's own projection.
  std::string plugin_parts;
  if (sim.world())
    for (const auto& pass : sim.world()->passes())
      if (pass.find("plug-in") != std::string::npos) plugin_parts += (plugin_parts.empty() ? "" : ", ") + pass;
  if (!plugin_parts.empty()) job.note += "  " + plugin_parts;
  for (const auto& set : o.sets)
    if (set.rfind("integrator=", 0) != 0) job.note += fmt::format("  {}", set);
  job.folder = rendering.folder();
  // The drawing's work, frame by frame, for the bar's time to go. A first-order scene's frame k draws
  // its curve through every state up to the one it shows, so later frames cost more: at one unit a
  // frame the bar said "~20 s to go" of a 95 s drawing (an audit of long runs). There a frame weighs
  // its states plus what a frame costs besides, in states: measured on lorenz at 640 × 480, 16 ms a
  // frame and 1.8 µs a state (the picture's cost besides grows with its pixels).
  std::vector<double> drawn_by(job.frame_index.size() + 1, 0.0);  // the work of frames 0 … k − 1
  const double per_frame = scene.is_mechanical() ? 1 : 8700.0 * width * height / (640.0 * 480.0);
  for (size_t k = 0; k < job.frame_index.size(); ++k)
    drawn_by[k + 1] = drawn_by[k] + per_frame + (scene.is_mechanical() ? 0 : static_cast<double>(job.frame_index[k]));
  progress.phase("drawing", 0, drawn_by.back());
  job.frame_done = [&](long k) { progress.update(drawn_by[static_cast<size_t>(std::clamp<long>(k, 0, frames))]); };
  if (const std::string error = drawing.render_frames(job); !error.empty()) {
    stop_if_interrupted();  // (a Ctrl-C that stopped the drawing is exit 130, not a failure)
    if (draw::out_of_memory(error)) throw std::bad_alloc();
    // (everything the user could get wrong was refused before the run)
    throw std::runtime_error(error);
  }
  progress.finish();
  if (!o.video.empty()) {
    progress.note("encoding the video (ffmpeg)");
    const std::string error = drawing.encode_video((fs::path(rendering.folder()) / "frame_%05d.png").string(), video_fps,
                                                   (fs::path(rendering.folder()) / video_name).string(), o.video);
    progress.finish();
    stop_if_interrupted();
    if (draw::out_of_memory(error)) throw std::bad_alloc();
    if (!error.empty()) throw std::runtime_error(error);
  }
  stop_if_interrupted();
  rendering.move_into_place(names);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  fmt::print("{} frame{}{} of {}x{} at {:g} per simulated {}{} ({:g} {} of {}{}) in {}/ ({:.1f} s)\n", frames,
             frames == 1 ? "" : "s", distinct < frames ? fmt::format(" ({} distinct)", distinct) : "", width, height, fps,
             one_unit, one_a_step ? ", one a step" : "", duration, unit, scene.name,
             speed == 1 ? "" : fmt::format(", played at {:g} {} a second", speed, unit),
             without_trailing_separators(o.out).string(), wall);

  if (!plugin_parts.empty()) fmt::print("passes       {}\n", plugin_parts);
  if (o.trails && scene.is_mechanical() && !trails_drawn)
    fmt::print("trails       none drawn: --trails draws scenes of at most {} bodies, and this one has {}\n",
               draw::RenderJob::kMostTrailedBodies, scene.mechanical->bodies.size());
  // (A first-order system is drawn as its curve, or its variables against time: no bodies to trail
  // or to give arrows. Both were taken without a word.)
  if ((o.trails || o.arrows) && !scene.is_mechanical())
    fmt::print("{:<12} none drawn: {} bodies; a first-order system is drawn as its curve or its variables against time\n",
               o.trails && o.arrows ? "trails/arrows" : o.trails ? "trails" : "arrows",
               o.trails && o.arrows ? "--trails and --arrows draw" : o.trails ? "--trails draws" : "--arrows draws");
  if (!o.video.empty())
    fmt::print("video        {}: {:.3g} s at {:.3g} frames a second\n",
               (without_trailing_separators(o.out) / video_name).string(), static_cast<double>(frames) / video_fps,
               video_fps);
  // An unstable run is drawn as it went (the frames show it), but it is not a run that went well.
  if (!std::isnan(not_finite_from)) {
    std::fflush(stdout);  // (the frames' line first, also through a pipe: it says where they are)
    tell("motus: the run failed: the state was no longer finite by t = {:g} ({}); the frames above show it as it "
         "went\n",
         not_finite_from, non_finite_suspect(sim, method, "a smaller step (--set dt=...)"));
    return 1;
  }
  return 0;
}

}  // namespace motus::cli
