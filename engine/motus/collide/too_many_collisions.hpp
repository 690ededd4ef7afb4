#pragma once

#include <stdexcept>

namespace motus {

// A step whose contacts did not end: more collisions in one step than any scene that can settle
// needs (a step so long that the balls cross many others in it, bodies that overlap without end,
// inelastic collapse, a plug-in's contacts that never part). Its message says which it was; the
// command that ran the scene names the scene's file before it (`motus run` exits 1).
class TooManyCollisions : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

}  // namespace motus
