// The course's first example, on the installed engine: a mass of 10 on a spring of
// stiffness 5, pulled to x = 20 and let go, stepped by explicit Euler with h = 1:
//   a = F/m = −k x / m;  x += v h;  v += a h
// prints t, x, v and a for t = 0 … 5 — the table of the course (x = 20, 20, 10, −10, −35, −55).
#include <cstdio>

#include "motus/simulation.hpp"

int main() {
  motus::MechanicalDescription bodies;
  bodies.dimensions = 1;
  bodies.bodies.push_back({/*mass*/ 10, /*position*/ {20}, /*velocity*/ {0}});
  motus::Spring spring;
  spring.a = 0;     // the body
  spring.b = -1;    // fixed at the anchor
  spring.anchor = {0, 0, 0};
  spring.stiffness = 5;
  bodies.forces.springs.push_back(spring);
  motus::SceneDescription scene;
  scene.name = "spring";
  scene.mechanical = bodies;

  motus::Simulation sim(scene, motus::Integrator::Euler);
  motus::Vector a(1);
  auto print_row = [&](const motus::Simulation&) {
    const double x = sim.state()[0], v = sim.state()[1];
    sim.mechanical_system()->acceleration(sim.time(), sim.state().head(1), sim.state().tail(1), a);  // F/m
    std::printf("%4g %8g %8g %8g\n", sim.time(), x, v, a[0]);
  };
  std::printf("%4s %8s %8s %8s\n", "t", "x", "v", "a");
  print_row(sim);
  sim.advance(/*end time*/ 5, /*h*/ 1, motus::Tolerance{}, print_row);
  return 0;
}
