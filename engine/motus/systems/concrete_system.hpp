#pragma once
// Calling a system by its concrete type, decided once per run: the Runge–Kutta family's
// derivative is then a direct call the compiler can inline, never a virtual call per
// evaluation, and a system that knows its size at compile time (static_size_of) gets its
// stages in registers.
//   with_concrete_system   a first-order system: the catalog's final classes (Lorenz, Rossler,
//                          Chen, Thomas, Aizawa), else the FirstOrderSystem interface (World2,
//                          whose derivative is out of line anyway, or any other);
//   with_first_order_view  point masses as y = [x; v]: one body in 1, 2 or 3 dimensions
//                          (OneBodyAsFirstOrder<D, Kinds>, for the kinds of force it has), else
//                          MechanicalAsFirstOrder.
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

// One body in D dimensions, compiled for the force kinds of the common exact problems — central
// gravity (Kepler), uniform gravity (free fall), gravity and drag (the projectile) — and for any
// forces otherwise: the same numbers either way, without the loops over kinds the scene lacks.
template <int D, class Fn>
void with_one_body(MechanicalSystem& system, Fn&& fn) {
  switch (system.one_body_force_kinds()) {
    case kCentralGravityForce: {
      OneBodyAsFirstOrder<D, kCentralGravityForce> one(system);
      return fn(one);
    }
    case kGravityForce: {
      OneBodyAsFirstOrder<D, kGravityForce> one(system);
      return fn(one);
    }
    case kGravityForce | kDragForce: {
      OneBodyAsFirstOrder<D, kGravityForce | kDragForce> one(system);
      return fn(one);
    }
    default: {
      OneBodyAsFirstOrder<D> one(system);
      return fn(one);
    }
  }
}

template <class Fn>
void with_first_order_view(MechanicalSystem& system, Fn&& fn) {
  if (system.particles() == 1) {
    switch (system.dimensions()) {
      case 1: return with_one_body<1>(system, fn);
      case 2: return with_one_body<2>(system, fn);
      case 3: return with_one_body<3>(system, fn);
      default: break;
    }
  }
  MechanicalAsFirstOrder any(system);
  fn(any);
}

}  // namespace motus
