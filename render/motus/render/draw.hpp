#pragma once
// Drawing a scene into a viewport of a canvas. Each function draws what the scene is:
//   mechanical scenes  2-D: balls as discs, walls (planes, boxes, segments), sticks, springs,
//                      pins, optional trails and velocity arrows, orthographic;
//                      3-D: lit spheres, a ground grid, box edges, cloth as shaded
//                      triangles (found from its sticks), in perspective;
//                      1-D: a spring as a mass on a zig-zag to its anchor, a pendulum as a
//                      rod and bob at angle x, anything else as beads on a line.
//   first-order        three variables (attractors): the 3-D trajectory coloured by time;
//                      otherwise (World2): each variable's time series, normalised by its
//                      largest magnitude over the run, with labels.
// Positions come as plain arrays (body i's coordinate k at i·d + k), so any engine's
// state can be drawn with the scene it was built from.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "motus/render/camera.hpp"
#include "motus/render/canvas.hpp"
#include "motus/render/shared_view.hpp"
#include "motus/scene.hpp"

namespace motus::render {

// The states of one run at increasing times: what a frame is drawn from.
struct Recording {
  std::vector<double> times;
  std::vector<std::vector<double>> states;  // [x; v] for mechanical scenes, y otherwise
  std::vector<double> energies;             // total energy per state (mechanical scenes; may be empty)

  void add(double t, std::span<const double> state, std::optional<double> energy = std::nullopt);
  size_t size() const { return times.size(); }
};

// Trails are drawn for scenes of at most this many bodies: beyond, paths cross each other and the
// picture is a tangle, not a path (and every body's trail is a line per recorded frame).
constexpr size_t kMostTrailedBodies = 64;

struct DrawOptions {
  Color background{250, 250, 247, 255};
  // The palette's place of body 0's colour (body_color): a comparison's bodies start after its first
  // three, which are the engines' colours in its plots (motus blue, Box2D orange, Bullet green); head_on's
  // orange ball read as Box2D's.
  int first_body_colour = 0;
  bool velocity_arrows = false;
  double arrow_seconds = 0.25;  // an arrow points to where the body would be this much later
  bool trails = false;          // drawn for scenes of at most kMostTrailedBodies bodies
  int trail_frames = 90;        // a trail shows the recorded states of this many frames' time (frame_interval)
  bool ground_grid = true;      // 3-D scenes
  // Where the 3-D ground grid lies (centre x, height y, centre z) and its half width; by
  // default from the frame's own bodies (fit_ground gives one for a whole run, which does
  // not move between frames).
  std::optional<Vec3> ground_centre;
  double ground_half_width = 0;
  bool overlay = true;          // draw_frame: scene name, time, energy drift in the corner
  // The time between two frames drawn (0: unknown): the overlay's time gets as many decimals as
  // tell them apart (at 240 frames a second, "t = 0.00 s" twice would not).
  double frame_interval = 0;
};

// One instant of a mechanical scene.
struct MechanicalFrame {
  std::span<const double> positions;                    // n·d numbers
  std::span<const double> velocities;                   // n·d numbers, or empty (no arrows)
  std::vector<std::span<const double>> trail;           // earlier positions, oldest first
};

// The colour of body i (a fixed palette; what the tests compare against).
Color body_color(int index);

// A camera that shows the whole run in the viewport: for 2-D/1-D scenes the walls and
// every recorded position (with a margin), for 3-D scenes and attractors a perspective
// view from above and to the side of the bounding box.
Camera fit_camera(const SceneDescription& scene, const Recording& recording, const Viewport& viewport);
// The same for several runs of one scene seen in one view (a comparison's engines in in_a_shared_view):
// every state of each, read where it is (a comparison of 10,000 balls holds hundreds of MB of them).
Camera fit_camera(const SceneDescription& scene, std::span<const Recording* const> runs, const Viewport& viewport);

// Which of several runs of one mechanical scene (a comparison's engines) one view can show together,
// by shared_view.hpp's rule: `ran[e]` says which ran, and of those, the run `reference` always, and
// each other one whose bodies stay within kFarthestInView times the reference's reach in every
// recorded state. A run that blew up would shrink the others to a dot in a view fitted to it.
std::vector<bool> in_a_shared_view(const SceneDescription& scene, const std::vector<Recording>& runs, size_t reference,
                                   std::vector<bool> ran);

// The ground grid for a whole run of a 3-D scene: under its lowest point (or on its
// ground plane), as wide as everything that moved. Sets options.ground_*.
void fit_ground(const SceneDescription& scene, const Recording& recording, DrawOptions& options);
void fit_ground(const SceneDescription& scene, std::span<const Recording* const> runs, DrawOptions& options);

void draw_mechanical(Canvas& canvas, const Viewport& viewport, const SceneDescription& scene,
                     const MechanicalFrame& frame, const Camera& camera, const DrawOptions& options = {});

// What a first-order scene's variables are called and mean, and what its time counts.
struct SeriesLabels {
  std::vector<std::string> names;     // one per variable
  std::vector<std::string> meanings;  // empty, or one per variable ("population (people)")
  std::string time_unit = "s";        // "s", or "year" for World2's calendar years
};

// An attractor's trajectory from recording[0] to recording[upto], coloured from dark purple
// (start) to yellow (now), viridis's ends, with a dot at the current state.
void draw_trajectory_3d(Canvas& canvas, const Viewport& viewport, const Recording& recording, size_t upto,
                        const Camera& camera, const SeriesLabels& labels, const DrawOptions& options = {});

// Each variable against time up to recording[upto], over the whole run's time axis.
void draw_time_series(Canvas& canvas, const Viewport& viewport, const Recording& recording, size_t upto,
                      const SeriesLabels& labels, const DrawOptions& options = {});

// Text in the viewport's top-left corner: a title, the time, and (when given) the
// relative energy drift (E − E₀)/|E₀| — or, for a scene that starts with E₀ = 0, E − E₀ in joules.
struct Overlay {
  std::string title;
  double time = 0;
  std::optional<double> energy_drift;
  std::string note;  // a further line (the integrator, say)
  std::string time_unit = "s";  // "year" (World2) shows the calendar year instead of t = … s
  bool energy_in_joules = false;  // energy_drift is E − E₀ in J (E₀ = 0: no scale to divide by)
  double time_step = 0;  // between the frames drawn (DrawOptions::frame_interval), or 0
};
void draw_overlay(Canvas& canvas, const Viewport& viewport, const Overlay& overlay);
// A scale bar at the bottom left of an orthographic (2-D) view: a round length in metres.
void draw_scale_bar(Canvas& canvas, const Viewport& viewport, const Camera& camera);
// The height of the band the overlay takes at the top of a viewport (fit_camera keeps 2-D
// scenes below it).
double overlay_height(const Viewport& viewport);

// One frame of `motus render`: background, the scene at recording[index] as above
// (with trails from the states before it), and the overlay.
void draw_frame(Canvas& canvas, const Viewport& viewport, const SceneDescription& scene, const Recording& recording,
                size_t index, const Camera& camera, const DrawOptions& options = {}, const std::string& note = "");

}  // namespace motus::render
