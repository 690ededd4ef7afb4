#pragma once
// The backend-neutral description of a scene: what a scene file says, after it has
// been read and checked. Every engine builds its world from this, never from JSON.
// The format is documented in docs/scene-format.md.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "motus/collide/colliders.hpp"
#include "motus/constrain/constraints.hpp"
#include "motus/forces/force_set.hpp"
#include "motus/systems/system_factory.hpp"

namespace motus {

struct BodyDescription {
  double mass = 1;
  std::vector<double> position;  // `dimensions` numbers
  std::vector<double> velocity;
  double radius = 0;       // a ball when > 0; a point mass (it still meets walls) when 0
  double restitution = 1;  // e; a pair's e is the product of the two (see collide/impulse.hpp)
};

struct MechanicalDescription {
  int dimensions = 2;
  std::vector<BodyDescription> bodies;
  ForceSet forces;
  Colliders colliders;                 // static walls (balls collide with each other without them)
  std::vector<StickConstraint> sticks; // Verlet distance constraints
  std::vector<PinConstraint> pins;     // bodies held at fixed points
  int constraint_iterations = 10;      // projection sweeps per projection
  int constraint_substeps = 1;         // Verlet steps of dt/n per step of dt, each with its projection
};

struct FirstOrderDescription {
  std::string type;                          // "lorenz", "world2", ... (see system_catalog.hpp), or "equations"
  std::map<std::string, double> parameters;  // every parameter, defaults filled in
  std::vector<double> initial;
  std::vector<std::string> variables;        // the state's names ("" or empty: the catalog's)
  // A system built outside the engine (the scene file's "equations"): when set, Simulation
  // makes its system with it instead of looking `type` up in the catalog.
  SystemFactory make;
};

// A state known to high accuracy at time t (e.g. tests/reference/lorenz.json).
struct ReferenceState {
  double t = 0;
  std::vector<double> state;
};

struct SceneDescription {
  std::string name;
  std::string description;
  std::optional<MechanicalDescription> mechanical;  // exactly one of these two
  std::optional<FirstOrderDescription> first_order;

  std::string integrator = "rk4";
  double dt = 0.01;
  double duration = 1;
  double start_time = 0;
  double rtol = 1e-6;
  double atol = 1e-9;
  double output_interval = 0;  // trajectory rows every this much time; 0: every step

  std::string exact;                     // an analytic solution the scene has ("" for none)
  std::vector<ReferenceState> reference; // reference states, where no analytic solution exists

  bool is_mechanical() const { return mechanical.has_value(); }
};

}  // namespace motus
