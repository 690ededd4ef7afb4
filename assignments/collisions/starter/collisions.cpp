// The collisions assignment: write each function below (the formulas are in
// assignments/collisions/README.md and above each declaration in collisions.hpp).
// Build and run the public tests with one command, from the folder motus was built in:
//   build/motus grade collisions THIS_FOLDER
#include "collisions.hpp"

#include <cmath>
#include <limits>

namespace student {

void collide_balls(double m_a, VectorInOut v_a, double m_b, VectorInOut v_b, VectorIn n, double e) {
  // TODO: J = −(1 + e) (v_b − v_a)·n / (1/m_a + 1/m_b); v_a −= (J/m_a) n; v_b += (J/m_b) n
  (void)m_a, (void)v_a, (void)m_b, (void)v_b, (void)n, (void)e;
}

void bounce_off_wall(VectorInOut v, VectorIn n, double e) {
  // TODO: the wall is infinitely heavy: take away (1 + e) times the velocity's part along n
  (void)v, (void)n, (void)e;
}

double time_of_impact(VectorIn p_a, VectorIn v_a, double r_a, VectorIn p_b, VectorIn v_b, double r_b) {
  // TODO: solve |p_b − p_a + (v_b − v_a) t| = r_a + r_b for the first t ≥ 0
  (void)p_a, (void)v_a, (void)r_a, (void)p_b, (void)v_b, (void)r_b;
  return std::numeric_limits<double>::infinity();
}

double time_of_impact_with_plane(VectorIn p, VectorIn v, double r, VectorIn n, double offset) {
  // TODO: the gap n·p − offset − r closes at the speed −n·v
  (void)p, (void)v, (void)r, (void)n, (void)offset;
  return std::numeric_limits<double>::infinity();
}

}  // namespace student
