#pragma once
// `motus compare --render`: the same instants of every engine as labelled panels side by
// side (motus | Box2D | Bullet), each with the time and its own energy drift, as PNG
// frames, a video (ffmpeg) and a contact sheet for the report.
#include <string>
#include <vector>

#include "comparison.hpp"

namespace motus::compare {

struct ComparisonPictures {
  long frames = 0;
  std::string video;          // file name in the folder, or "" when ffmpeg is missing
  std::string contact_sheet;  // file name in the folder
  std::string warning;        // one line for the user, or ""
};

// Draws runs[*].frames into `folder`/frames/frame_NNNNN.png (panels of width × height),
// then `folder`/comparison.mp4 and `folder`/contact_sheet.png. Throws render::RenderError
// when there is no OpenGL.
ComparisonPictures draw_comparison(const std::string& folder, const SceneDescription& scene,
                                   const std::vector<EngineRun>& runs, int width, int height, double fps);

}  // namespace motus::compare
