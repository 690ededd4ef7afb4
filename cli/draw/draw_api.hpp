#pragma once
// The boundary between `motus` and its drawing module, motus-draw.so.
//
// Drawing needs OpenGL, and OSMesa brings LLVM, libz3, ICU and libxml2 with it: tens of ms of
// dynamic loading before main() (docs/architecture.md has the figure). Only `motus render` and
// `motus compare` draw (compare its report's first_and_last.png on every run, every frame with
// --render), so everything that touches OpenGL lives in a module that `motus` loads (dlopen)
// only for them, and every other command starts without it.
//
// The boundary is plain data, and no exception crosses it: each call returns "" when it
// worked, else one line saying what went wrong. The module is built from this tree with the
// same compiler, so std:: types pass as they are; kApiVersion guards against a module left
// over from another build.
#include <functional>
#include <string>
#include <vector>

#include "motus/scene.hpp"

namespace motus::draw {

constexpr int kApiVersion = 7;
// What a call returns, exactly, when memory ran out (std::bad_alloc in the module, FreeType's
// Out_Of_Memory): the caller fails the run as out of memory (exit 1), never "pictures skipped"
// nor a bad font or a bad option.
constexpr const char* kOutOfMemory = "out of memory";
inline bool out_of_memory(const std::string& error) { return error == kOutOfMemory; }
// The function the module exports (extern "C", so dlsym finds it by this name).
constexpr const char* kEntryPoint = "motus_draw_api";

// One run's recorded states at increasing times: [x; v] for bodies, y for first-order systems.
struct Frames {
  std::vector<double> times;
  std::vector<std::vector<double>> states;
  std::vector<double> energies;  // total energy of each state (bodies only; may be empty)
};

// `motus render`: frame k shows frames->states[frame_index[k]]. The drawing takes the frames (they are
// moved from): it draws them where they are, not a copy of them.
struct RenderJob {
  const SceneDescription* scene = nullptr;
  Frames* frames = nullptr;
  std::vector<size_t> frame_index;
  int width = 640, height = 480, supersample = 2;
  bool trails = false, arrows = false;
  // Trails are drawn for scenes of at most this many bodies (render::kMostTrailedBodies: the same
  // number, checked where both are seen, draw_module.cpp).
  static constexpr size_t kMostTrailedBodies = 64;
  std::string note;    // the overlay's last line (integrator, --set overrides)
  std::string folder;  // frame_00000.png, ... are written here (it exists)
  std::function<void(long)> frame_done;  // after each frame is written (progress)
};

// `motus compare`: one panel per engine (first_and_last.png; with --render every frame too).
struct Panel {
  std::string engine;                    // "motus", "box2d", ... (the panel's overlay)
  std::string label;                     // above the panel ("Box2D 2.4.1, float")
  Frames frames;                         // empty when the engine could not run the scene
  std::vector<std::string> unsupported;  // why not, one line each
};

struct ComparisonJob {
  const SceneDescription* scene = nullptr;
  std::vector<Panel> panels;
  int width = 480, height = 360;  // each panel
  double fps = 30;
  std::string folder;  // first_and_last.png, frames/, comparison.mp4 and contact_sheet.png go here (it exists)
  std::function<void(long done, long total)> progress;
  // Only the first and the last instant, as first_and_last.png (no frames/, no video, no
  // contact sheet). first_and_last.png, the picture every report has, is drawn either way.
  bool first_and_last_only = false;
};

struct ComparisonPictures {
  long frames = 0;
  std::string video;          // file name in the folder, or "" when ffmpeg is missing
  std::string first_and_last;  // file name in the folder: the first and the last instant (always drawn)
  std::string contact_sheet;   // file name in the folder: three instants (not when first_and_last_only), or ""
  std::string warning;        // one line for the user, or ""
  // Set when the error returned is a picture that could not be written (a full disk), or a video
  // ffmpeg failed to make: the report is not whole, and the run fails — not a "pictures skipped"
  // warning over a truncated PNG, nor "video skipped" over a video --render asked for.
  bool write_failed = false;
};

struct Api {
  int version = kApiVersion;
  // Whether a canvas of this size (and the overlay's font) can be had, before any work is done.
  std::string (*check)(int width, int height, int supersample);
  std::string (*render_frames)(const RenderJob& job);
  // frame_pattern is printf-style ("DIR/frame_%05d.png"); format is "mp4" or "gif".
  std::string (*encode_video)(const std::string& frame_pattern, double fps, const std::string& out,
                              const std::string& format);
  // Takes the panels' frames (they are moved from): it draws them where they are, not a copy of them
  // (a comparison of 40,000 balls at 60 frames a second kept a third copy of a gigabyte of states).
  std::string (*draw_comparison)(ComparisonJob& job, ComparisonPictures& pictures);
  // SIGKILL to the programs the module is waiting for (ffmpeg): async-signal-safe, for motus
  // stopping at once (the module has its own copy of motus::process, and so its own list of them).
  void (*kill_running_programs)() noexcept;
  // SIGTERM to them, and SIGKILL after a short grace (process::stop_running_programs): for the first
  // interrupt, so that motus does not wait for an ffmpeg that caught the same Ctrl-C. Async-signal-safe.
  void (*stop_running_programs)() noexcept;
};

}  // namespace motus::draw
