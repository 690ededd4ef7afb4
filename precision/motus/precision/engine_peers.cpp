#include "motus/precision/engine_peers.hpp"

#include <cmath>

#include "motus/compare/backends/backend.hpp"
#include "motus/precision/motus_sweep.hpp"
#include "motus/precision/run_times.hpp"
#include "motus/simulation.hpp"

namespace motus::precision {

Curve sweep_engine(const SceneDescription& scene, const std::string& name, const Sweep& sweep) {
  Curve c;
  c.method = name;
  c.engine = name;
  c.adaptive = false;
  const Method symplectic_euler = Integrator::SymplecticEuler;  // what the peers do (ignored by them)
  for (double dt : engine_steps()) {
    const long steps = fixed_step_count(sweep.end - scene.start_time, dt);
    Point p;
    p.h = dt;
    // One run (Sweep::round says which), the world built outside its time.
    std::unique_ptr<compare::Backend> engine = compare::make_backend(name);
    try {
      engine->build(scene, symplectic_euler, dt);
    } catch (const compare::Unsupported& e) {
      c.unsupported.clear();
      for (const auto& element : e.elements()) c.unsupported += (c.unsupported.empty() ? "" : "; ") + element;
      c.points.clear();
      return c;
    }
    if (c.description.empty()) c.description = engine->version() + ", semi-implicit Euler";
    Stopwatch watch;
    watch.start();
    for (long i = 0; i < steps; ++i) engine->step();
    watch.stop();
    compare::Snapshot s;
    engine->read(s);
    Vector y(static_cast<Eigen::Index>(s.x.size() + s.v.size()));
    for (size_t i = 0; i < s.x.size(); ++i) y[static_cast<Eigen::Index>(i)] = s.x[i];
    for (size_t i = 0; i < s.v.size(); ++i) y[static_cast<Eigen::Index>(s.x.size() + i)] = s.v[i];
    p.t_end = scene.start_time + static_cast<double>(steps) * dt;
    p.steps = steps;
    p.evaluations = steps;  // the scene's forces, applied once per step
    p.error = state_error(scene, y, p.t_end);
    p.seconds = p.median_seconds = watch.seconds();
    c.points.push_back(p);
    if (sweep.point_done) sweep.point_done(static_cast<double>(steps));
  }
  return c;
}

}  // namespace motus::precision
