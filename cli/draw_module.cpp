#include "draw_module.hpp"

#include "interrupt.hpp"
#include "module_loader.hpp"

namespace motus::cli {
namespace {

const draw::Api& load() {
  const draw::Api& api = load_module<draw::Api>("MOTUS_DRAW_MODULE", MOTUS_DRAW_MODULE_NAME, MOTUS_DRAW_MODULE_INSTALLED,
                                                draw::kEntryPoint, draw::kApiVersion, "drawing module", "motus-draw");
  on_stop_at_once(api.kill_running_programs);  // (its ffmpeg goes with motus)
  on_interrupt_also(api.stop_running_programs);  // (and is not waited for after a Ctrl-C)
  if (interrupted()) api.stop_running_programs();  // (one that came before the module was loaded)
  return api;
}

}  // namespace

const draw::Api& draw_module() {
  static const draw::Api& api = load();
  return api;
}

}  // namespace motus::cli
