#pragma once
// An offscreen OpenGL canvas: an OSMesa context (software OpenGL through llvmpipe)
// drawing into a buffer in memory. OSMesa has no multisampling, so a canvas renders at
// `supersample` times its size and image() averages each supersample × supersample
// block: discs, lines and triangles come out anti-aliased. Text is queued and drawn
// with FreeType on the resolved image, on top of everything (see text.hpp).
//
// Several viewports of one canvas can hold several drawings (panels side by side):
// begin(viewport) points OpenGL at that rectangle only.
#include <cstdint>
#include <string>
#include <vector>

#include "motus/render/image.hpp"
#include "motus/render/text.hpp"

namespace motus::render {

class Canvas {
public:
  // Throws RenderError when OSMesa cannot give a context for this size or OpenGL does
  // not answer (glGetString(GL_VERSION) is null). Setting the environment variable
  // MOTUS_RENDER_FAIL_CONTEXT=1 makes the context creation fail on purpose (for tests).
  Canvas(int width, int height, int supersample = 2);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  int supersample() const { return supersample_; }
  Viewport full() const { return {0, 0, width_, height_}; }

  // Fills (part of) the canvas with a colour, clears its depth and its queued text (the text
  // anchored inside that part).
  void clear(Color color);
  void clear(const Viewport& area, Color color);

  // Makes this canvas's context current and points OpenGL's viewport and scissor at
  // `area` (canvas pixels from the top-left). Projection and modelview are the caller's;
  // glOrtho(0, area.width, area.height, 0, -1, 1) then draws in the area's pixels.
  void begin(const Viewport& area);

  // Queues text (baseline at canvas pixel y), drawn on the resolved image.
  void text(int x, int y, std::string text, const TextStyle& style = {});
  // How many texts are queued (a frame drawn again over a cleared canvas queues its own again:
  // the tests check that nothing piles up from frame to frame).
  size_t queued_texts() const { return text_.size(); }

  // Finishes OpenGL, averages the supersamples, puts row 0 at the top (OSMesa's buffer
  // is bottom-up) and draws the queued text.
  Image image();
  void image(Image& out);

  // The OpenGL version string of the context (e.g. "4.5 (Compatibility Profile) Mesa 22.3.6").
  std::string gl_version() const { return gl_version_; }

private:
  struct QueuedText {
    int x, y;
    std::string text;
    TextStyle style;
  };
  int width_, height_, supersample_;
  std::vector<std::uint8_t> buffer_;  // (width·s) × (height·s) RGBA, bottom row first
  void* context_ = nullptr;           // OSMesaContext
  std::vector<QueuedText> text_;
  std::string gl_version_;
};

}  // namespace motus::render
