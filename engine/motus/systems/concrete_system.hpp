#pragma once
// Calling a system by its concrete type, decided once per run: the Runge–Kutta family's
// derivative is then a direct call the compiler can inline, never a virtual call per
// evaluation, and a system that knows its size at compile time (static_size_of) gets its
// stages in registers.
//   with_concrete_system   a first-order system: the catalog's final classes (Lorenz, Rossler,
//                          Chen, Thomas, Aizawa), else the FirstOrderSystem interface (World2,
//                          whose derivative is out of line anyway, or any other);
//   with_first_order_view  point masses as y = [x; v]: one body in 1, 2 or 3 dimensions
//                          (OneBodyAsFirstOrder<D>), else MechanicalAsFirstOrder.
// Simulation::advance uses them, and so do the peers of `motus bench precision`, which are
// thereby given the same right-hand side.
#include "motus/systems/attractors.hpp"
#include "motus/systems/mechanical_as_first_order.hpp"

namespace motus {

template <class Fn>
void with_concrete_system(FirstOrderSystem& system, Fn&& fn) {
  if (auto* s = dynamic_cast<Lorenz*>(&system)) return fn(*s);
  if (auto* s = dynamic_cast<Rossler*>(&system)) return fn(*s);
  if (auto* s = dynamic_cast<Chen*>(&system)) return fn(*s);
  if (auto* s = dynamic_cast<Thomas*>(&system)) return fn(*s);
  if (auto* s = dynamic_cast<Aizawa*>(&system)) return fn(*s);
  fn(system);
}

template <class Fn>
void with_first_order_view(MechanicalSystem& system, Fn&& fn) {
  if (system.particles() == 1) {
    switch (system.dimensions()) {
      case 1: {
        OneBodyAsFirstOrder<1> one(system);
        return fn(one);
      }
      case 2: {
        OneBodyAsFirstOrder<2> one(system);
        return fn(one);
      }
      case 3: {
        OneBodyAsFirstOrder<3> one(system);
        return fn(one);
      }
      default: break;
    }
  }
  MechanicalAsFirstOrder any(system);
  fn(any);
}

}  // namespace motus
