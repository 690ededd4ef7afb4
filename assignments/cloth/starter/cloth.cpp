// The cloth assignment: write each function below (the formulas are in
// assignments/cloth/README.md and above each declaration in cloth.hpp).
// Build and run the public tests with one command, from the folder motus was built in:
//   build/motus grade cloth THIS_FOLDER
#include "cloth.hpp"

namespace student {

void project_stick(VectorInOut x_a, VectorInOut x_b, double w_a, double w_b, double length) {
  // TODO: delta = x_b − x_a; move x_a by w_a/(w_a + w_b) and x_b by w_b/(w_a + w_b) of the
  // error (|delta| − length), along delta
  (void)x_a, (void)x_b, (void)w_a, (void)w_b, (void)length;
}

void project_wall(VectorInOut x, double r, const Wall& wall) {
  // TODO: if wall.normal·x − wall.offset − r < 0, move x back along wall.normal by that much
  (void)x, (void)r, (void)wall;
}

void satisfy_constraints(Bodies& bodies, const Constraints& constraints) {
  // TODO: constraints.iterations sweeps over the sticks (project_stick) and the walls
  // (project_wall); pinned bodies get weight 0 and end on their pins.
  (void)bodies, (void)constraints;
}

}  // namespace student
