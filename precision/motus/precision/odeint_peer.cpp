#include "motus/precision/odeint_peer.hpp"

#include <boost/numeric/odeint.hpp>
#include <boost/version.hpp>

#include <array>
#include <cmath>
#include <optional>
#include <type_traits>

#include "motus/precision/motus_sweep.hpp"
#include "motus/precision/run_times.hpp"
#include "motus/scene_error.hpp"
#include "motus/simulation.hpp"
#include "motus/systems/concrete_system.hpp"

// Boost.Odeint 1.74's controlled_runge_kutta copies a default-made stepper, whose std::array work
// arrays are not set yet (they are written before they are read): GCC 12 warns about the copy,
// attributing it to this file. Only that warning is silenced, only here.
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

namespace motus::precision {
namespace {

namespace ode = boost::numeric::odeint;

// A state as Odeint keeps it: a std::array of N numbers, or a std::vector.
template <int N>
using OdeintState = std::conditional_t<N == Eigen::Dynamic, std::vector<double>, std::array<double, static_cast<size_t>(N == Eigen::Dynamic ? 1 : N)>>;

template <class State>
State make_state(const Vector& y) {
  State s{};
  if constexpr (requires { s.resize(0); }) s.resize(static_cast<size_t>(y.size()));
  for (size_t i = 0; i < s.size(); ++i) s[i] = y[static_cast<Eigen::Index>(i)];
  return s;
}

template <class State>
Vector to_vector(const State& s) {
  Vector y(static_cast<Eigen::Index>(s.size()));
  for (size_t i = 0; i < s.size(); ++i) y[static_cast<Eigen::Index>(i)] = s[i];
  return y;
}

template <class State>
Eigen::Map<const Vector> view(const State& s) {
  return Eigen::Map<const Vector>(s.data(), static_cast<Eigen::Index>(s.size()));
}
template <class State>
Eigen::Map<Vector> view(State& s) {
  return Eigen::Map<Vector>(s.data(), static_cast<Eigen::Index>(s.size()));
}

// motus's system, called the way Odeint calls a system: f(x, dxdt, t).
template <class System>
struct SameRightHandSide {
  System* f;
  template <class State>
  void operator()(const State& x, State& dxdt, double t) const {
    f->derivative(t, view(x), view(dxdt));
  }
};

// The derivative evaluations a system has counted.
template <class System>
long& evaluations_of(System& f) {
  if constexpr (requires { f.mechanical(); }) return f.mechanical().evaluations;
  else return f.evaluations;
}

struct Outcome {
  Vector state;
  double t_end = 0;
  long steps = 0;
};

// One run of the point (Sweep::round says which): `run` integrates from a fresh initial state,
// starting and stopping the watch around its steps (its stepper and state are made before, as
// motus's Simulation is built outside its time), and returns the outcome.
template <class Run>
Point measure(const SceneDescription& scene, long& evaluations, double h, double tol, Run run) {
  Point p;
  p.h = h;
  p.tolerance = tol;
  const long before = evaluations;
  Stopwatch watch;
  Outcome o;
  try {
    o = run(watch);
  } catch (const std::exception& e) {  // Odeint gave up (too many step size adjustments)
    p.failed = std::string("odeint: ") + e.what();
    return p;
  }
  p.t_end = o.t_end;
  p.steps = o.steps;
  p.evaluations = evaluations - before;
  try {
    p.error = state_error(scene, o.state, o.t_end);
  } catch (const std::exception& e) {  // (no exact state where it ended: that point, not the run)
    p.failed = e.what();
    return p;
  }
  p.seconds = p.median_seconds = watch.seconds();
  return p;
}

Curve curve(const std::string& name, const std::string& description, bool adaptive) {
  Curve c;
  c.method = "odeint:" + name;
  c.engine = "odeint";
  c.description = description;
  c.adaptive = adaptive;
  return c;
}

// One body under central gravity alone (Kepler), as an Odeint user writes its right-hand side:
// the parameters copied into the function object, the derivative assigned whole. Through motus's
// one-body right-hand side (SameRightHandSide over OneBodyAsFirstOrder), shaped for motus's stage
// vectors (one vector store of the acceleration), Odeint paid 2–2.5× per evaluation on its
// std::arrays where motus's own steppers pay nothing (an audit, 2026-12-07). The same formula and
// order of operations as CentralGravity::add_forces and acceleration_of_one_body: the same numbers.
template <int D>
struct CentralGravityForOdeint {
  std::array<double, 3> centre{};
  double mu = 0, softening = 0, mass = 0, inverse_mass = 0;
  long* evaluations = nullptr;
  // a = F/m at x (one evaluation): also what Odeint's symplectic RKN gets on Kepler.
  void acceleration(const double* x, double* a) const {
    ++*evaluations;
    double r[D];
    for (int k = 0; k < D; ++k) r[k] = x[k] - centre[k];
    double s2 = r[0] * r[0];
    for (int k = 1; k < D; ++k) s2 += r[k] * r[k];
    if (softening != 0) s2 += softening * softening;
    const double scale = -mu * mass / (s2 * std::sqrt(s2));
    for (int k = 0; k < D; ++k) a[k] = (scale * r[k]) * inverse_mass;
  }
  void operator()(const std::array<double, 2 * D>& y, std::array<double, 2 * D>& dydt, double) const {
    std::array<double, 2 * D> d;
    for (int k = 0; k < D; ++k) d[k] = y[D + k];
    acceleration(y.data(), d.data() + D);
    dydt = d;
  }
};

// A strange attractor's right-hand side likewise (Lorenz, Rössler, Chen, Thomas, Aizawa): the system's
// numbers copied in (a copy of it), its own formula (rate(), attractors.hpp: the same numbers) on
// Odeint's std::arrays, the derivative assigned whole. Through SameRightHandSide Odeint paid 1.15–1.2×
// per evaluation on Lorenz in this command.
template <class System>
struct AttractorForOdeint {
  System system;
  long* evaluations = nullptr;
  void operator()(const std::array<double, 3>& s, std::array<double, 3>& d, double) const {
    ++*evaluations;
    std::array<double, 3> out;
    system.rate(s, out);
    d = out;
  }
};

// The three Runge–Kutta steppers on the right-hand side rhs (y = [x; v] for point masses), whose
// evaluations `evaluations` counts.
template <class State, class Rhs>
void runge_kutta_on(const SceneDescription& scene, const Rhs& rhs, long& evaluations, const Vector& y0,
                    const Sweep& sweep, std::vector<Curve>& curves) {
  const double t0 = scene.start_time, end = sweep.end;

  Curve rk4 = curve("runge_kutta4", "Odeint's classic fourth-order Runge-Kutta, fixed step", false);
  for (const double h : fixed_steps(scene, sweep)) {
    const long n = fixed_step_count(end - t0, h);
    rk4.points.push_back(measure(scene, evaluations, h, 0, [&](Stopwatch& watch) {
      ode::runge_kutta4<State> stepper;
      State x = make_state<State>(y0);
      double t = t0;
      watch.start();
      for (long i = 0; i < n; ++i) {
        stepper.do_step(rhs, x, t, h);
        t = t0 + static_cast<double>(i + 1) * h;
      }
      watch.stop();
      return Outcome{to_vector(x), t, n};
    }));
    if (sweep.point_done) sweep.point_done(static_cast<double>(n));
  }
  curves.push_back(std::move(rk4));

  auto controlled = [&](Curve c, auto make_stepper) {
    for (double tol : tolerances(sweep)) {
      c.points.push_back(measure(scene, evaluations, sweep.dt, tol, [&](Stopwatch& watch) {
        auto stepper = make_stepper(tol);
        State x = make_state<State>(y0);
        watch.start();
        const long steps = static_cast<long>(ode::integrate_adaptive(stepper, rhs, x, t0, end, sweep.dt));
        watch.stop();
        return Outcome{to_vector(x), end, steps};
      }));
      if (sweep.point_done) sweep.point_done(nominal_steps(scene, sweep, sweep.dt));
    }
    curves.push_back(std::move(c));
  };
  // What make_controlled(tol, tol, stepper) makes.
  auto controller = []<class Stepper>(double tol) {
    using Controlled = ode::controlled_runge_kutta<Stepper>;
    return Controlled(typename Controlled::error_checker_type(tol, tol));
  };
  controlled(curve("runge_kutta_dopri5", "Odeint's Dormand-Prince 5(4), controlled (as make_controlled)", true),
             [&](double tol) { return controller.template operator()<ode::runge_kutta_dopri5<State>>(tol); });
  controlled(curve("runge_kutta_fehlberg78", "Odeint's Runge-Kutta-Fehlberg 7(8), controlled (as make_controlled)", true),
             [&](double tol) { return controller.template operator()<ode::runge_kutta_fehlberg78<State>>(tol); });
}

// The three on the first-order system f, by its concrete type.
template <class System>
void runge_kutta(const SceneDescription& scene, System& f, const Vector& y0, const Sweep& sweep,
                 std::vector<Curve>& curves) {
  runge_kutta_on<OdeintState<static_size_of<System>>>(scene, SameRightHandSide<System>{&f}, evaluations_of(f), y0,
                                                       sweep, curves);
}

// Kepler's right-hand side for Odeint when the scene is one body in D dimensions under one central
// gravity and nothing else; none otherwise.
template <int D>
std::optional<CentralGravityForOdeint<D>> kepler_right_hand_side(MechanicalSystem& m) {
  const ForceSet& f = m.forces();
  if (m.particles() != 1 || m.dimensions() != D || m.one_body_force_kinds() != kCentralGravityForce ||
      f.central_gravity.size() != 1 || f.central_gravity[0].body > 0)
    return std::nullopt;
  const CentralGravity& g = f.central_gravity[0];
  CentralGravityForOdeint<D> rhs;
  rhs.centre = g.centre;
  rhs.mu = g.mu;
  rhs.softening = g.softening;
  rhs.mass = m.masses()[0];
  rhs.inverse_mass = 1 / m.masses()[0];
  rhs.evaluations = &m.evaluations;
  return rhs;
}

// The Runge–Kutta steppers on Kepler's right-hand side (kepler_right_hand_side); false when the
// scene is not one body in D dimensions under central gravity alone.
template <int D>
bool runge_kutta_on_kepler(const SceneDescription& scene, MechanicalSystem& m, const Vector& y0, const Sweep& sweep,
                           std::vector<Curve>& curves) {
  const auto rhs = kepler_right_hand_side<D>(m);
  if (!rhs) return false;
  runge_kutta_on<std::array<double, 2 * D>>(scene, *rhs, m.evaluations, y0, sweep, curves);
  return true;
}

// McLachlan's symplectic RKN on point masses: q = x, p = v, dq/dt = p, dp/dt = a(q), with
// acceleration(q, dpdt) counting its evaluations in `evaluations`.
template <int D, class Acceleration>  // one body in D dimensions, or D = Eigen::Dynamic: any number of bodies
void symplectic_rkn(const SceneDescription& scene, long& evaluations, Acceleration acceleration, const Vector& y0,
                    const Sweep& sweep, Curve& c) {
  using Coor = OdeintState<D>;
  const Eigen::Index n = y0.size() / 2;
  const double t0 = scene.start_time;
  for (const double h : fixed_steps(scene, sweep)) {
    const long steps = fixed_step_count(sweep.end - t0, h);
    c.points.push_back(measure(scene, evaluations, h, 0, [&](Stopwatch& watch) {
      ode::symplectic_rkn_sb3a_mclachlan<Coor> stepper;
      Coor q = make_state<Coor>(y0.head(n)), p = make_state<Coor>(y0.tail(n));
      double t = t0;
      watch.start();
      for (long i = 0; i < steps; ++i) {
        stepper.do_step(acceleration, std::make_pair(std::ref(q), std::ref(p)), t, h);
        t = t0 + static_cast<double>(i + 1) * h;
      }
      watch.stop();
      Vector y(2 * n);
      y << to_vector(q), to_vector(p);
      return Outcome{y, t, steps};
    }));
    if (sweep.point_done) sweep.point_done(static_cast<double>(steps));
  }
}

// The RKN on the system's own forces: on Kepler the function object the Runge–Kutta steppers get
// (through the general force loop it paid for kinds of force Kepler lacks, where motus's methods
// are compiled for central gravity); otherwise motus's acceleration, of one body or of any.
template <int D>
void symplectic_rkn_on(const SceneDescription& scene, MechanicalSystem& system, const Vector& y0, const Sweep& sweep,
                       Curve& c) {
  using Coor = OdeintState<D>;
  if constexpr (D != Eigen::Dynamic) {
    if (const auto rhs = kepler_right_hand_side<D>(system)) {
      symplectic_rkn<D>(scene, system.evaluations,
                        [rhs = *rhs](const Coor& q, Coor& dpdt) { rhs.acceleration(q.data(), dpdt.data()); }, y0, sweep, c);
      return;
    }
  }
  const Coor zero = make_state<Coor>(Vector::Zero(y0.size() / 2));  // the forces do not read velocities
  symplectic_rkn<D>(scene, system.evaluations,
                    [&](const Coor& q, Coor& dpdt) {
                      if constexpr (D == Eigen::Dynamic)
                        system.acceleration(0, view(q), view(zero), view(dpdt));
                      else
                        system.acceleration_of_one_body<D>(0, q.data(), zero.data(), dpdt.data());
                    },
                    y0, sweep, c);
}

}  // namespace

std::string odeint_version() {
  return "Boost.Odeint, Boost " + std::to_string(BOOST_VERSION / 100000) + "." + std::to_string(BOOST_VERSION / 100 % 1000) +
         "." + std::to_string(BOOST_VERSION % 100);
}

std::vector<Curve> sweep_odeint(const SceneDescription& scene, const Sweep& sweep) {
  // A simulation owns the system, built exactly as for motus's own runs; only its system and
  // initial state are used.
  std::optional<Simulation> built;
  try {
    built.emplace(scene, Integrator::Rk4);
  } catch (const SceneError& e) {  // collisions or constraints: a Runge–Kutta method cannot run them
    std::vector<Curve> curves;
    for (const char* name : kOdeintMethods) {
      Curve c = curve(name, "", false);
      c.unsupported = std::string("the scene's collisions or constraints: ") + e.what();
      curves.push_back(std::move(c));
    }
    return curves;
  }
  Simulation& sim = *built;
  const Vector y0 = sim.state();
  std::vector<Curve> curves;
  auto run = [&](auto& f) { runge_kutta(scene, f, y0, sweep, curves); };
  if (MechanicalSystem* m = sim.mechanical_system()) {
    if (!runge_kutta_on_kepler<1>(scene, *m, y0, sweep, curves) && !runge_kutta_on_kepler<2>(scene, *m, y0, sweep, curves) &&
        !runge_kutta_on_kepler<3>(scene, *m, y0, sweep, curves))
      with_first_order_view(*m, run);
  } else {
    with_concrete_system(*sim.first_order_system(), [&](auto& f) {
      using System = std::decay_t<decltype(f)>;
      if constexpr (requires(std::array<double, 3> a) { f.rate(a, a); }) {
        const AttractorForOdeint<System> rhs{f, &f.evaluations};
        runge_kutta_on<std::array<double, 3>>(scene, rhs, f.evaluations, y0, sweep, curves);
      } else {
        run(f);
      }
    });
  }

  Curve rkn = curve("symplectic_rkn_sb3a_mclachlan",
                    "Odeint's symplectic Runge-Kutta-Nystrom of order 4 (McLachlan), fixed step", false);
  if (MechanicalSystem* m = sim.mechanical_system()) {
    const ForceSet& f = m->forces();
    bool damped = !f.drag.empty();
    for (const auto& s : f.springs) damped = damped || s.damping != 0;
    if (damped) {
      rkn.unsupported = "forces that depend on velocity (drag, damping): dq/dt = p, dp/dt = a(q) only";
    } else if (m->particles() == 1 && m->dimensions() == 1) {
      symplectic_rkn_on<1>(scene, *m, y0, sweep, rkn);
    } else if (m->particles() == 1 && m->dimensions() == 2) {
      symplectic_rkn_on<2>(scene, *m, y0, sweep, rkn);
    } else if (m->particles() == 1 && m->dimensions() == 3) {
      symplectic_rkn_on<3>(scene, *m, y0, sweep, rkn);
    } else {
      symplectic_rkn_on<Eigen::Dynamic>(scene, *m, y0, sweep, rkn);
    }
  } else {
    rkn.unsupported = "symplectic: needs a mechanical scene (bodies)";
  }
  curves.push_back(std::move(rkn));
  return curves;
}

}  // namespace motus::precision
