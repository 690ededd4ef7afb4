#pragma once
// Text with a real font: FreeType rasterises a TrueType file (by default DejaVu Sans from
// Debian's fonts-dejavu-core) with anti-aliasing, drawn onto an Image.
#include <memory>
#include <string>

#include "motus/render/image.hpp"

namespace motus::render {

class Font {
public:
  // Throws RenderError naming the file and the fix when it is missing or unreadable.
  explicit Font(const std::string& path);
  ~Font();
  Font(const Font&) = delete;
  Font& operator=(const Font&) = delete;
  const std::string& path() const { return path_; }

  // $MOTUS_FONT if set, else /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf; loaded
  // once. Throws RenderError if the file is missing.
  static const Font& default_font();
  static std::string default_font_path();

  struct Impl;
  Impl& impl() const { return *impl_; }

private:
  std::string path_;
  std::unique_ptr<Impl> impl_;
};

enum class Align { left, center, right };

struct TextStyle {
  double size = 14;                 // pixel height of the em square
  Color color{20, 20, 20, 255};
  Align align = Align::left;        // relative to x
  const Font* font = nullptr;       // nullptr: Font::default_font()
};

// Draws UTF-8 `text` with its baseline at y and its left / centre / right at x.
void draw_text(Image& image, int x, int y, const std::string& text, const TextStyle& style = {});
// Advance width of `text` in pixels.
int text_width(const std::string& text, const TextStyle& style = {});

}  // namespace motus::render
