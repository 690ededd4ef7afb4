#pragma once
// Loading motus-draw.so, the drawing module (draw/draw_api.hpp), when a command draws.
#include "draw/draw_api.hpp"

namespace motus::cli {

// The module's functions. Loaded on first use and kept for the rest of the process. Throws
// InputError (one line, exit 2) when the module is missing, is not motus's drawing module,
// or was built for another version of motus.
const draw::Api& draw_module();

}  // namespace motus::cli
