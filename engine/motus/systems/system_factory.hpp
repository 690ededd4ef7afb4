#pragma once
// A first-order system made outside the engine: the scene file's "equations" system (right-hand
// sides written as expressions, parsed by scene/'s expression library) reaches the engine as a
// factory in its description, so the engine builds and steps it without knowing how it is made.
// The engine stays Eigen-only; each run calls the factory once.
#include <functional>
#include <memory>

namespace motus {

class FirstOrderSystem;

using SystemFactory = std::function<std::unique_ptr<FirstOrderSystem>()>;

}  // namespace motus
