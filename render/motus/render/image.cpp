#include "motus/render/image.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

namespace motus::render {

Image::Image(int w, int h, Color fill_color)
    : width(w), height(h), rgba(static_cast<size_t>(w) * static_cast<size_t>(h) * 4) {
  fill({0, 0, w, h}, fill_color);
}

Color Image::pixel(int x, int y) const {
  const std::uint8_t* p = &rgba[(static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4];
  return {p[0], p[1], p[2], p[3]};
}

void Image::set_pixel(int x, int y, Color c) {
  if (x < 0 || y < 0 || x >= width || y >= height) return;
  std::uint8_t* p = &rgba[(static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4];
  p[0] = c.r, p[1] = c.g, p[2] = c.b, p[3] = c.a;
}

void Image::blend_pixel(int x, int y, Color c, double alpha) {
  if (x < 0 || y < 0 || x >= width || y >= height) return;
  const double a = std::clamp(alpha, 0.0, 1.0) * c.a / 255.0;
  std::uint8_t* p = &rgba[(static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4];
  auto mix = [a](std::uint8_t dst, std::uint8_t src) {
    return static_cast<std::uint8_t>(std::lround(dst + (src - dst) * a));
  };
  p[0] = mix(p[0], c.r), p[1] = mix(p[1], c.g), p[2] = mix(p[2], c.b);
  p[3] = static_cast<std::uint8_t>(std::lround(p[3] + (255 - p[3]) * a));
}

void Image::fill(const Viewport& area, Color c) {
  const int x0 = std::max(0, area.x), x1 = std::min(width, area.x + area.width);
  const int y0 = std::max(0, area.y), y1 = std::min(height, area.y + area.height);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) set_pixel(x, y, c);
}

void Image::paste(const Image& source, int x, int y) {
  for (int sy = 0; sy < source.height; ++sy) {
    const int ty = y + sy;
    if (ty < 0 || ty >= height) continue;
    const int sx0 = std::max(0, -x), sx1 = std::min(source.width, width - x);
    if (sx1 <= sx0) continue;
    std::copy_n(&source.rgba[(static_cast<size_t>(sy) * static_cast<size_t>(source.width) + static_cast<size_t>(sx0)) * 4],
                static_cast<size_t>(sx1 - sx0) * 4,
                &rgba[(static_cast<size_t>(ty) * static_cast<size_t>(width) + static_cast<size_t>(x + sx0)) * 4]);
  }
}

namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

// libpng's error handler must not return: it long-jumps back to png_jmpbuf. The
// functions that set the jump point hold nothing with a destructor.
void png_failure(png_structp png, png_const_charp message) {
  auto* text = static_cast<char*>(png_get_error_ptr(png));
  std::snprintf(text, 256, "%s", message);
  longjmp(png_jmpbuf(png), 1);
}

bool png_write_all(png_structp png, png_infop info, std::FILE* file, const Image* image, int level) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, file);
  png_set_compression_level(png, level);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);  // one cheap filter: most of the speed, most of the size
  png_set_IHDR(png, info, static_cast<png_uint_32>(image->width), static_cast<png_uint_32>(image->height), 8,
               PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image->height; ++y)
    png_write_row(png, &image->rgba[static_cast<size_t>(y) * static_cast<size_t>(image->width) * 4]);
  png_write_end(png, nullptr);
  return true;
}

bool png_read_header(png_structp png, png_infop info, std::FILE* file, int* width, int* height) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, file);
  png_read_info(png, info);
  png_set_expand(png);
  png_set_strip_16(png);
  png_set_gray_to_rgb(png);
  png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
  png_read_update_info(png, info);
  *width = static_cast<int>(png_get_image_width(png, info));
  *height = static_cast<int>(png_get_image_height(png, info));
  return true;
}

bool png_read_rows(png_structp png, Image* image) {
  if (setjmp(png_jmpbuf(png))) return false;
  for (int y = 0; y < image->height; ++y)
    png_read_row(png, &image->rgba[static_cast<size_t>(y) * static_cast<size_t>(image->width) * 4], nullptr);
  png_read_end(png, nullptr);
  return true;
}

}  // namespace

void write_png(const std::string& path, const Image& image, int compression_level) {
  // Every failure names the system's reason (a full disk: "No space left on device"), as the
  // command line's other writes do; libpng's own says only "Write Error".
  auto failed = [&](int error) { return RenderError(path + ": could not be written (" + std::strerror(error) + ")"); };
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "wb"));
  if (!file) throw failed(errno);
  char message[256] = "out of memory";
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, message, png_failure, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  const bool ok = info && png_write_all(png, info, file.get(), &image, std::clamp(compression_level, 0, 9));
  const int write_error = errno;
  png_destroy_write_struct(&png, &info);
  if (!ok && std::ferror(file.get())) throw failed(write_error);
  if (!ok) throw RenderError(path + ": libpng: " + message);
  if (std::fflush(file.get()) != 0) throw failed(errno);
  if (std::fclose(file.release()) != 0) throw failed(errno);
}

Image read_png(const std::string& path) {
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) throw RenderError(path + ": cannot be read");
  char message[256] = "out of memory";
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, message, png_failure, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  int width = 0, height = 0;
  Image image;
  bool ok = info && png_read_header(png, info, file.get(), &width, &height);
  if (ok) {
    image = Image(width, height);
    ok = png_read_rows(png, &image);
  }
  png_destroy_read_struct(&png, &info, nullptr);
  if (!ok) throw RenderError(path + ": libpng: " + message);
  return image;
}

}  // namespace motus::render
