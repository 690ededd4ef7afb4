#pragma once
// The report's replay: every engine's kept frames (EngineRun::frames) played back side by side in
// index.html, in the browser, from the file system. Two files go into the report folder:
//   replay.js       the player (compare/replay/replay.js, embedded at build time): plain canvas
//   replay-data.js  `window.MOTUS_REPLAY = {...};` — the scene's geometry and every engine's frames,
//                   a script rather than JSON to fetch, because a page opened from file:// cannot fetch
// and index.html gets the section that shows them (replay_section), loading both with <script src>.
// The layout the player keeps (docs/cli.md, "The replay") is in compare/replay/replay.js.
#include <string>
#include <vector>

#include "motus/compare/comparison.hpp"

namespace motus::compare {

// At most this many bodies are drawn (and written): beyond it every k-th body, k = ceil(n / limit).
inline constexpr long kReplayBodyLimit = 20000;

// Which engines the replay's one view is fitted to: those with frames whose bodies stay near the first
// such engine's (render/motus/render/shared_view.hpp: within kFarthestInView times its reach). A peer
// that blew up is left out, and its panel says that its bodies go out of view. Found once for a report,
// and given to replay_view, write_replay and replay_section.
std::vector<bool> engines_in_view(const SceneDescription& scene, const std::vector<EngineRun>& runs);

// The part of the scene the replay shows, in scene coordinates (x right, y up; 3-D seen along −z,
// 1-D on the line y = 0): the walls (boxes and segments) if there are any, else every body's disc
// at every kept frame of the engines in view, plus the point of each plane nearest to that; never empty.
struct ReplayView {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
ReplayView replay_view(const SceneDescription& scene, const std::vector<EngineRun>& runs, const std::vector<bool>& in_view);

// Writes replay.js and replay-data.js into `folder` (which must exist); a file that cannot be
// written whole throws std::runtime_error naming it. `scene` must be mechanical.
void write_replay(const std::string& folder, const SceneDescription& scene, const std::vector<EngineRun>& runs,
                  const std::vector<bool>& in_view);

// The replay's CSS (its fixed layout, scoped to #replay), for the page's <style> in <head>: a
// <style> element is not allowed inside a <section>.
std::string replay_style();

// The <section id="replay"> for index.html — a panel per engine in engine order (a canvas, or the
// reasons an engine could not run the scene), the controls, notes on what is drawn — followed by
// the two <script src> tags.
std::string replay_section(const SceneDescription& scene, const std::vector<EngineRun>& runs,
                           const std::vector<bool>& in_view);

}  // namespace motus::compare
