#include "motus/render/canvas.hpp"

#include <GL/osmesa.h>
#include <sys/mman.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdlib>
#include <new>
#include <string>

namespace motus::render {

namespace {

constexpr long kMaxBufferBytes = 1L << 30;  // refuse before allocating more than 1 GiB

// What OSMesa needs of the address space to make a context and draw its first frames, with room:
// it makes them within about 12 MB on Debian 12's Mesa 22 (measured: a render with 7 MB of room
// under `ulimit -v` died, with 12 MB it drew every frame).
constexpr size_t kContextRoomBytes = 32UL << 20;

// Whether the address space (under a limit such as `ulimit -v`) has that room now. Mesa does not
// check its allocations while it makes a context: without the room, motus died of SIGSEGV inside
// OSMesaCreateContextExt, its partial folders left, instead of saying that memory ran out.
bool room_for_a_context() {
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return true;
  void* room = ::mmap(nullptr, kContextRoomBytes, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (room == MAP_FAILED) return false;  // (a mapping of no pages still counts against RLIMIT_AS)
  ::munmap(room, kContextRoomBytes);
  return true;
}

bool failure_requested() {
  const char* env = std::getenv("MOTUS_RENDER_FAIL_CONTEXT");
  return env && std::string(env) == "1";
}

}  // namespace

Canvas::Canvas(int width, int height, int supersample) : width_(width), height_(height), supersample_(supersample) {
  if (width < 1 || height < 1) throw RenderError("canvas size must be at least 1 x 1 pixels");
  if (supersample < 1 || supersample > 8) throw RenderError("supersampling must be from 1 to 8");
  const long w = static_cast<long>(width) * supersample, h = static_cast<long>(height) * supersample;
  if (static_cast<double>(w) * static_cast<double>(h) * 4 > static_cast<double>(kMaxBufferBytes))  // (a long overflows at 2e9 a side)
    // (Named as the option, as every other bad option is: the size is the user's, not OSMesa's.)
    throw RenderError("--size: " + std::to_string(width) + "x" + std::to_string(height) + " pixels" +
                      (supersample > 1 ? " at --supersample " + std::to_string(supersample) : std::string()) +
                      " needs an offscreen buffer over 1 GiB; choose a smaller --size");
  // Mesa would keep a cache of compiled shaders in ~/.cache/mesa_shader_cache: a write outside
  // the folder the user gave, for shaders that take no time to compile. (Unless the user set it.)
  ::setenv("MESA_SHADER_CACHE_DISABLE", "true", 0);
  // Under a limit on the address space (`ulimit -v`), llvmpipe's rasterizer threads — one per core,
  // each with its stack and bins — did not check their allocations, and motus died of SIGSEGV in
  // OSMesa while drawing the report's first frame (a ball gas within 450 MB). With that limit,
  // llvmpipe rasterizes in this thread (unless the user chose LP_NUM_THREADS); what then runs out is
  // motus's to report (out of memory, exit 1).
  if (rlimit limit{}; ::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    ::setenv("LP_NUM_THREADS", "0", 0);
  if (!room_for_a_context()) throw std::bad_alloc();  // (out of memory, exit 1: as any allocation motus makes)
  OSMesaContext context = failure_requested() ? nullptr : OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  if (!context)
    // (OSMesa is there — this module is linked to it — and memory was checked above: what is left is
    // Mesa's own setup. "Install libosmesa6" was the message, for a library that was installed.)
    throw RenderError("OSMesa could not create an offscreen OpenGL context: Mesa, which is installed, refused (a MESA_ "
                      "or GALLIUM_ setting in the environment, or a broken Mesa install)");
  context_ = context;
  buffer_.assign(static_cast<size_t>(w * h * 4), 0);
  if (!OSMesaMakeCurrent(context, buffer_.data(), GL_UNSIGNED_BYTE, static_cast<GLsizei>(w), static_cast<GLsizei>(h))) {
    OSMesaDestroyContext(context);
    context_ = nullptr;
    throw RenderError("--size: " + std::to_string(width) + "x" + std::to_string(height) + " pixels at --supersample " +
                      std::to_string(supersample) + " is larger than OSMesa draws (a " + std::to_string(w) + " x " +
                      std::to_string(h) + " pixel context); choose a smaller --size");
  }
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  if (!version) {
    OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    OSMesaDestroyContext(context);
    context_ = nullptr;
    throw RenderError("OpenGL does not answer (glGetString(GL_VERSION) is null): the program must link libOSMesa and "
                      "not libGL, whose GL entry points would otherwise come first and draw nothing");
  }
  gl_version_ = version;
  // OSMesa makes a context of any size, but draws only within its limits.
  GLint max_width = 0, max_height = 0, max_viewport[2] = {0, 0};
  OSMesaGetIntegerv(OSMESA_MAX_WIDTH, &max_width);
  OSMesaGetIntegerv(OSMESA_MAX_HEIGHT, &max_height);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, max_viewport);
  const long limit_w = std::min<long>(max_width, max_viewport[0]), limit_h = std::min<long>(max_height, max_viewport[1]);
  if (w > limit_w || h > limit_h) {
    OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    OSMesaDestroyContext(context);
    context_ = nullptr;
    throw RenderError("--size: " + std::to_string(width) + "x" + std::to_string(height) + " pixels at --supersample " +
                      std::to_string(supersample) + " is " + std::to_string(w) + " x " + std::to_string(h) +
                      ", past what OSMesa draws (" + std::to_string(limit_w) + " x " + std::to_string(limit_h) +
                      "): choose a smaller --size or --supersample");
  }
  OSMesaPixelStore(OSMESA_Y_UP, 1);  // row 0 of the buffer is the bottom row
  glDisable(GL_DITHER);
  clear({255, 255, 255, 255});
}

Canvas::~Canvas() {
  if (!context_) return;
  if (OSMesaGetCurrentContext() == static_cast<OSMesaContext>(context_)) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
  OSMesaDestroyContext(static_cast<OSMesaContext>(context_));
}

void Canvas::begin(const Viewport& a) {
  auto* context = static_cast<OSMesaContext>(context_);
  if (OSMesaGetCurrentContext() != context)
    OSMesaMakeCurrent(context, buffer_.data(), GL_UNSIGNED_BYTE, width_ * supersample_, height_ * supersample_);
  const int s = supersample_;
  const int bottom = height_ - (a.y + a.height);  // OpenGL counts rows from the bottom
  glViewport(a.x * s, bottom * s, a.width * s, a.height * s);
  glEnable(GL_SCISSOR_TEST);
  glScissor(a.x * s, bottom * s, a.width * s, a.height * s);
}

void Canvas::clear(Color color) {
  clear(full(), color);
  text_.clear();
}

void Canvas::clear(const Viewport& area, Color c) {
  begin(area);
  glClearColor(c.r / 255.0f, c.g / 255.0f, c.b / 255.0f, c.a / 255.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  // The text queued in this area goes with it (a panel drawn again must not keep the overlay of the
  // panel drawn there before): the text whose anchor lies inside it, an anchor off the canvas
  // counting as at its nearest edge (a chart's legend anchored below a small frame was kept, and
  // drawn again, every frame: world2's 1,001st frame drew a thousand legends, 100 ms).
  std::erase_if(text_, [&](const QueuedText& t) {
    const int x = std::clamp(t.x, 0, width_ - 1), y = std::clamp(t.y, 0, height_ - 1);
    return x >= area.x && x < area.x + area.width && y >= area.y && y < area.y + area.height;
  });
}

void Canvas::text(int x, int y, std::string text, const TextStyle& style) {
  text_.push_back({x, y, std::move(text), style});
}

Image Canvas::image() {
  Image out;
  image(out);
  return out;
}

void Canvas::image(Image& out) {
  begin(full());
  glFinish();
  if (out.width != width_ || out.height != height_) out = Image(width_, height_);
  const int s = supersample_;
  const size_t row_bytes = static_cast<size_t>(width_) * static_cast<size_t>(s) * 4;
  const unsigned samples = static_cast<unsigned>(s * s), half = samples / 2;
  // The rounded average of a block's sum, looked up: a division per byte was half the resolve's time.
  std::vector<std::uint8_t> average(255 * samples + 1);
  for (unsigned sum = 0; sum < average.size(); ++sum) average[sum] = static_cast<std::uint8_t>((sum + half) / samples);
  std::vector<unsigned> sums(static_cast<size_t>(width_) * 4);
  for (int y = 0; y < height_; ++y) {
    std::fill(sums.begin(), sums.end(), 0u);
    for (int j = 0; j < s; ++j) {
      // Output row y (from the top) covers buffer rows counted from the bottom.
      const size_t buffer_row = static_cast<size_t>((height_ - 1 - y) * s + j);
      const std::uint8_t* p = &buffer_[buffer_row * row_bytes];
      for (int x = 0; x < width_; ++x)
        for (int i = 0; i < s; ++i, p += 4) {
          unsigned* q = &sums[static_cast<size_t>(x) * 4];
          q[0] += p[0], q[1] += p[1], q[2] += p[2], q[3] += p[3];
        }
    }
    std::uint8_t* o = &out.rgba[static_cast<size_t>(y) * static_cast<size_t>(width_) * 4];
    for (size_t k = 0; k < sums.size(); ++k) o[k] = average[sums[k]];
  }
  for (const auto& t : text_) draw_text(out, t.x, t.y, t.text, t.style);
}

}  // namespace motus::render
