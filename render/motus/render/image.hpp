#pragma once
// An RGBA image in memory (8 bits a channel, rows top to bottom), what every drawing
// ends as, and its PNG file.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace motus::render {

// A failure of the rendering machinery or its environment (no OSMesa context, no
// font file, no ffmpeg): the command line reports it as bad input (exit 2).
class RenderError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct Color {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
  friend bool operator==(const Color&, const Color&) = default;
};

// A rectangle of a canvas or image in pixels, from its top-left corner.
struct Viewport {
  int x = 0, y = 0, width = 0, height = 0;
};

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4, row 0 at the top

  Image() = default;
  Image(int width, int height, Color fill = {255, 255, 255, 255});
  Color pixel(int x, int y) const;
  void set_pixel(int x, int y, Color c);
  // Source-over blend of c with coverage alpha in [0, 1] (c.a is multiplied in).
  void blend_pixel(int x, int y, Color c, double alpha);
  void fill(const Viewport& area, Color c);
  // Copies `source` with its top-left corner at (x, y), clipped.
  void paste(const Image& source, int x, int y);
};

// Writes an 8-bit RGBA PNG. Deterministic: the same image gives the same bytes (no
// time stamp). zlib level 0..9 with the "sub" filter only: level 1 was as fast as any and no
// larger than 3 on frames when it was chosen (bench/bench_render times this default only).
void write_png(const std::string& path, const Image& image, int compression_level = 1);
// Reads an 8-bit PNG (any colour type libpng can expand to RGBA), for tests and tools.
Image read_png(const std::string& path);

}  // namespace motus::render
