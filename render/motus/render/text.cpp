#include "motus/render/text.hpp"

#include <ft2build.h>
#include <sys/mman.h>
#include FT_FREETYPE_H

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <new>

namespace motus::render {

struct Font::Impl {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
  double size = 0;  // the pixel size currently set on the face
  std::mutex mutex;

  void set_size(double pixels) {
    if (pixels == size) return;
    FT_Set_Char_Size(face, 0, static_cast<FT_F26Dot6>(std::lround(pixels * 64)), 72, 72);
    size = pixels;
  }
};

namespace {

// Whether memory ran out when FreeType failed: its own Out_Of_Memory, or — FreeType tries each of
// its font drivers in turn, and one that could not allocate may leave "unknown file format" as the
// answer (found under `ulimit -v`: DejaVuSans.ttf "could not be read") — when 64 MB cannot be had.
bool memory_ran_out(FT_Error error) {
  if (error == FT_Err_Out_Of_Memory) return true;
  constexpr size_t kProbe = size_t{64} << 20;
  void* probe = ::mmap(nullptr, kProbe, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (probe == MAP_FAILED) return true;
  ::munmap(probe, kProbe);
  return false;
}

}  // namespace

Font::Font(const std::string& path) : path_(path), impl_(std::make_unique<Impl>()) {
  if (!std::filesystem::exists(path))
    throw RenderError("font file " + path +
                      " not found: install the Debian package fonts-dejavu-core, or set MOTUS_FONT to a .ttf file");
  // Memory running out (a limit such as `ulimit -v`) is not a bad font: std::bad_alloc, as every
  // other allocation that fails (the run fails, saying so).
  if (const FT_Error error = FT_Init_FreeType(&impl_->library); error != 0) {
    impl_->library = nullptr;
    if (memory_ran_out(error)) throw std::bad_alloc();
    throw RenderError("FreeType could not be initialised");
  }
  if (const FT_Error error = FT_New_Face(impl_->library, path.c_str(), 0, &impl_->face); error != 0) {
    FT_Done_FreeType(impl_->library);
    impl_->library = nullptr;
    impl_->face = nullptr;
    if (memory_ran_out(error)) throw std::bad_alloc();
    throw RenderError("font file " + path + " could not be read by FreeType (is it a TrueType/OpenType font?)");
  }
}

Font::~Font() {
  if (impl_->face) FT_Done_Face(impl_->face);
  if (impl_->library) FT_Done_FreeType(impl_->library);
}

std::string Font::default_font_path() {
  if (const char* env = std::getenv("MOTUS_FONT"); env && *env) return env;
  return MOTUS_DEFAULT_FONT;  // set by CMake
}

const Font& Font::default_font() {
  static const Font font(default_font_path());
  return font;
}

namespace {

// Decodes one UTF-8 code point (invalid bytes become U+FFFD).
char32_t next_code_point(const std::string& s, size_t& i) {
  const auto c = static_cast<unsigned char>(s[i++]);
  if (c < 0x80) return c;
  int extra = c >= 0xF0 ? 3 : c >= 0xE0 ? 2 : c >= 0xC0 ? 1 : -1;
  if (extra < 0) return 0xFFFD;
  char32_t cp = c & (0x3F >> extra);
  for (; extra > 0; --extra) {
    if (i >= s.size() || (static_cast<unsigned char>(s[i]) & 0xC0) != 0x80) return 0xFFFD;
    cp = (cp << 6) | (static_cast<unsigned char>(s[i++]) & 0x3F);
  }
  return cp;
}

// Walks the glyphs of `text`; draw(glyph slot, pen x) for each, returns the advance.
template <class F>
int walk(Font::Impl& f, const std::string& text, double size, F&& draw) {
  f.set_size(size);
  long pen = 0;  // 26.6 fixed point
  FT_UInt previous = 0;
  const bool kerning = FT_HAS_KERNING(f.face);
  for (size_t i = 0; i < text.size();) {
    const char32_t cp = next_code_point(text, i);
    const FT_UInt index = FT_Get_Char_Index(f.face, cp);
    if (kerning && previous && index) {
      FT_Vector delta;
      FT_Get_Kerning(f.face, previous, index, FT_KERNING_DEFAULT, &delta);
      pen += delta.x;
    }
    if (FT_Load_Glyph(f.face, index, FT_LOAD_DEFAULT) != 0) continue;
    draw(f.face->glyph, static_cast<int>((pen + 32) >> 6));
    pen += f.face->glyph->advance.x;
    previous = index;
  }
  return static_cast<int>((pen + 32) >> 6);
}

const Font& font_of(const TextStyle& style) { return style.font ? *style.font : Font::default_font(); }

}  // namespace

int text_width(const std::string& text, const TextStyle& style) {
  auto& f = font_of(style).impl();
  std::lock_guard lock(f.mutex);
  return walk(f, text, style.size, [](FT_GlyphSlot, int) {});
}

void draw_text(Image& image, int x, int y, const std::string& text, const TextStyle& style) {
  auto& f = font_of(style).impl();
  std::lock_guard lock(f.mutex);
  int origin = x;
  if (style.align != Align::left) {
    const int width = walk(f, text, style.size, [](FT_GlyphSlot, int) {});
    origin -= style.align == Align::center ? width / 2 : width;
  }
  walk(f, text, style.size, [&](FT_GlyphSlot glyph, int pen) {
    if (FT_Render_Glyph(glyph, FT_RENDER_MODE_NORMAL) != 0) return;
    const FT_Bitmap& bitmap = glyph->bitmap;
    const int left = origin + pen + glyph->bitmap_left, top = y - glyph->bitmap_top;
    for (unsigned row = 0; row < bitmap.rows; ++row)
      for (unsigned col = 0; col < bitmap.width; ++col) {
        const unsigned char coverage = bitmap.buffer[static_cast<long>(row) * bitmap.pitch + col];
        if (coverage)
          image.blend_pixel(left + static_cast<int>(col), top + static_cast<int>(row), style.color, coverage / 255.0);
      }
  });
}

}  // namespace motus::render
