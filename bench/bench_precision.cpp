// The two costs behind `motus bench precision --peers odeint` (issue 12), as ratios measured side
// by side in one run:
//   step cost         one rk4 step of motus's through the point-mass path (the scene's Kepler, one body in 2-D,
//                     OneBodyAsFirstOrder<2, kCentralGravityForce>) against one of Boost.Odeint's runge_kutta4 on a
//                     hand-written Kepler right-hand side in a std::array — the way Odeint is used at its
//                     fastest. Both take 4 evaluations a step, so this is the cost of 4 evaluations
//                     and the stage arithmetic around them, not of one evaluation alone; the goal is
//                     ≤ 1.2. The same on Lorenz (motus's compiled Lorenz by its concrete type).
//   loop overhead     Simulation::advance over 1,000 steps against the bare stepper's loop over the
//                     same concrete system; the goal is ≤ 1.1.
// Odeint is a peer: it is used here and in precision/, never in engine/.
#include <benchmark/benchmark.h>

#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <string>

#include "motus/integrate/rk4.hpp"
#include "motus/scene_file/scene_file.hpp"
#include "motus/simulation.hpp"
#include "motus/systems/attractors.hpp"
#include "motus/systems/concrete_system.hpp"
#include "ratio_reporter.hpp"

namespace {

using namespace motus;
using motus::bench::minimum;
namespace ode = boost::numeric::odeint;

constexpr double kKeplerStep = 1e-3, kLorenzStep = 1e-3;
constexpr int kLoopSteps = 1000;

SceneDescription shipped(const std::string& name) {
  return load_scene(std::string(MOTUS_SCENES_DIR) + "/" + name + ".json");
}

// ---- Kepler: x'' = −μ x / |x|³ with the scene's μ and start.
using Kepler4 = std::array<double, 4>;

struct KeplerByHand {
  double mu;
  void operator()(const Kepler4& y, Kepler4& dydt, double /*t*/) const {
    const double r2 = y[0] * y[0] + y[1] * y[1];
    const double a = -mu / (r2 * std::sqrt(r2));
    dydt = {y[2], y[3], a * y[0], a * y[1]};
  }
};

void KeplerOdeintRk4(benchmark::State& state) {
  const SceneDescription scene = shipped("kepler");
  const auto& body = scene.mechanical->bodies[0];
  const KeplerByHand rhs{scene.mechanical->forces.central_gravity[0].mu};
  Kepler4 y = {body.position[0], body.position[1], body.velocity[0], body.velocity[1]};
  ode::runge_kutta4<Kepler4> stepper;
  double t = 0;
  for (auto _ : state) {
    stepper.do_step(rhs, y, t, kKeplerStep);
    t += kKeplerStep;
    benchmark::DoNotOptimize(y.data());
  }
}
BENCHMARK(KeplerOdeintRk4)->Name("Kepler/odeint_rk4_by_hand")->ComputeStatistics("min", minimum);

void KeplerMotusRk4(benchmark::State& state) {
  Simulation sim(shipped("kepler"), Integrator::Rk4);
  Vector y = sim.state();
  Rk4 stepper;
  stepper.resize(4);
  // What Simulation::advance steps for Kepler (with_first_order_view: one body, central gravity only).
  OneBodyAsFirstOrder<2, kCentralGravityForce> f(*sim.mechanical_system());
  double t = 0;
  for (auto _ : state) {
    stepper.step(f, t, kKeplerStep, y);
    t += kKeplerStep;
    benchmark::DoNotOptimize(y.data());
  }
}
BENCHMARK(KeplerMotusRk4)->Name("Kepler/motus_rk4_point_mass")->ComputeStatistics("min", minimum);

// ---- Lorenz: the compiled system against the same three lines by hand.
using Lorenz3 = std::array<double, 3>;

void LorenzOdeintRk4(benchmark::State& state) {
  auto rhs = [](const Lorenz3& s, Lorenz3& d, double) {
    constexpr double sigma = 10, rho = 28, beta = 8.0 / 3;
    d = {sigma * (s[1] - s[0]), s[0] * (rho - s[2]) - s[1], s[0] * s[1] - beta * s[2]};
  };
  Lorenz3 y = {1, 1, 1};
  ode::runge_kutta4<Lorenz3> stepper;
  double t = 0;
  for (auto _ : state) {
    stepper.do_step(rhs, y, t, kLorenzStep);
    t += kLorenzStep;
    benchmark::DoNotOptimize(y.data());
  }
}
BENCHMARK(LorenzOdeintRk4)->Name("Lorenz/odeint_rk4_by_hand")->ComputeStatistics("min", minimum);

void LorenzMotusRk4(benchmark::State& state) {
  Lorenz f;
  Vector y = Vector::Ones(3);
  Rk4 stepper;
  stepper.resize(3);
  double t = 0;
  for (auto _ : state) {
    stepper.step(f, t, kLorenzStep, y);
    t += kLorenzStep;
    benchmark::DoNotOptimize(y.data());
  }
}
BENCHMARK(LorenzMotusRk4)->Name("Lorenz/motus_rk4")->ComputeStatistics("min", minimum);

// ---- The loop: 1,000 bare steps against Simulation::advance over the same 1,000 steps.
template <class System>
void bare_loop(benchmark::State& state, System& f, Vector y, double h) {
  Rk4 stepper;
  stepper.resize(static_cast<int>(y.size()));
  for (auto _ : state) {
    const double t0 = 0;
    for (long i = 0; i < kLoopSteps; ++i) stepper.step(f, t0 + static_cast<double>(i) * h, h, y);
    benchmark::DoNotOptimize(y.data());
  }
}

void simulation_loop(benchmark::State& state, const SceneDescription& scene, double h) {
  Simulation sim(scene, Integrator::Rk4);
  for (auto _ : state) sim.advance(sim.time() + kLoopSteps * h, h, Tolerance{});
  benchmark::DoNotOptimize(sim.state().data());
}

void LorenzBareStepper(benchmark::State& state) {
  Lorenz f;
  bare_loop(state, f, Vector::Ones(3), kLorenzStep);
}
BENCHMARK(LorenzBareStepper)->Name("Lorenz/rk4_bare_1000_steps")->ComputeStatistics("min", minimum);

void LorenzSimulation(benchmark::State& state) { simulation_loop(state, shipped("lorenz"), kLorenzStep); }
BENCHMARK(LorenzSimulation)->Name("Lorenz/rk4_simulation_1000_steps")->ComputeStatistics("min", minimum);

void KeplerBareStepper(benchmark::State& state) {
  Simulation sim(shipped("kepler"), Integrator::Rk4);
  OneBodyAsFirstOrder<2, kCentralGravityForce> f(*sim.mechanical_system());
  bare_loop(state, f, sim.state(), kKeplerStep);
}
BENCHMARK(KeplerBareStepper)->Name("Kepler/rk4_bare_1000_steps")->ComputeStatistics("min", minimum);

void KeplerSimulation(benchmark::State& state) { simulation_loop(state, shipped("kepler"), kKeplerStep); }
BENCHMARK(KeplerSimulation)->Name("Kepler/rk4_simulation_1000_steps")->ComputeStatistics("min", minimum);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  motus::bench::RatioReporter reporter;
  reporter.add_ratio("Kepler: one rk4 step, motus point-mass path / Odeint by hand (goal <= 1.2)",
                     "Kepler/motus_rk4_point_mass", "Kepler/odeint_rk4_by_hand");
  reporter.add_ratio("Lorenz: one rk4 step, motus / Odeint by hand (goal <= 1.2)", "Lorenz/motus_rk4",
                     "Lorenz/odeint_rk4_by_hand");
  reporter.add_ratio("Lorenz: Simulation::advance / the bare stepper (goal <= 1.1)", "Lorenz/rk4_simulation_1000_steps",
                     "Lorenz/rk4_bare_1000_steps");
  reporter.add_ratio("Kepler: Simulation::advance / the bare stepper (goal <= 1.1)", "Kepler/rk4_simulation_1000_steps",
                     "Kepler/rk4_bare_1000_steps");
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
