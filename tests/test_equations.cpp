// ODEs written in the scene file ("system": {"type": "equations", ...}, docs/scene-format.md),
// parsed once per run by muparser, against what they must equal:
//   - Lorenz written as expressions (scenes/lorenz_equations.json) against the compiled Lorenz of
//     the catalog (scenes/lorenz.json), step by step, for every Runge–Kutta method: a peer measured
//     in the same test. They do the same arithmetic, so they agree to rounding, and Lorenz's largest
//     Lyapunov exponent (≈ 0.906, tests/reference/integrators.md) bounds how far rounding can grow.
//   - the Arenstorf orbit (scenes/arenstorf.json) returns to y0 at T = 17.0652165601579625588917206249
//     (tests/reference/integrators.md, [HNW] ch. II): rk45 at a tight tolerance, within 1e-8;
//   - Van der Pol at mu = 1 (scenes/van_der_pol.json) settles on its limit cycle, whose period is
//     6.6632868593231 (tests/reference/integrators.md): measured between upward zero crossings, to 1e-8.
//   - bad equations: the loader's error names the field (system.equations.y, ...) and the column.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "motus/integrate/integrator_catalog.hpp"
#include "motus/scene_error.hpp"
#include "motus/scene_file/scene_file.hpp"
#include "motus/simulation.hpp"

namespace {

using motus::Integrator;

std::string scene_path(const std::string& name) { return std::string(MOTUS_SCENES_DIR) + "/" + name + ".json"; }

double max_difference(const motus::Vector& a, const motus::Vector& b) { return (a - b).cwiseAbs().maxCoeff(); }

// ---------------------------------------------------------------------------------------------
// Lorenz: expressions against the compiled system.

struct Agreement {
  double largest = 0;  // the largest |difference| of any variable at any step
  long steps = 0;
  bool identical = true;
};

Agreement lorenz_agreement(Integrator integrator, long steps, double dt) {
  const auto compiled_scene = motus::load_scene(scene_path("lorenz"));
  const auto expression_scene = motus::load_scene(scene_path("lorenz_equations"));
  EXPECT_TRUE(static_cast<bool>(expression_scene.first_order->make));
  EXPECT_FALSE(static_cast<bool>(compiled_scene.first_order->make));
  motus::Simulation compiled(compiled_scene, integrator), expressions(expression_scene, integrator);
  Agreement a;
  const motus::Tolerance tolerance{1e-9, 1e-9};
  for (long i = 1; i <= steps; ++i) {
    const double end = static_cast<double>(i) * dt;
    compiled.advance(end, dt, tolerance);
    expressions.advance(end, dt, tolerance);
    const double d = max_difference(compiled.state(), expressions.state());
    a.largest = std::max(a.largest, d);
    a.identical = a.identical && compiled.state() == expressions.state();
  }
  a.steps = expressions.steps();
  EXPECT_EQ(compiled.steps(), expressions.steps());
  EXPECT_EQ(compiled.evaluations(), expressions.evaluations());  // the same method, the same calls
  return a;
}

// Rounding (2.2e-16 relative, states of size ≤ 50) grown at most by e^{λ t} with λ = 0.906
// (integrators.md) over t: the most that rounding alone can account for.
double rounding_bound(double t) { return 2.2e-16 * 50 * std::exp(0.906 * t); }

TEST(EquationsLorenz, MatchesTheCompiledSystemToRoundingOverTenThousandSteps) {
  const double dt = 1e-3;
  const long steps = 10000;  // the issue: 10^4 steps (t = 10)
  const Agreement a = lorenz_agreement(Integrator::Rk4, steps, dt);
  std::printf("  rk4, %ld steps of %g: largest difference %.3e (identical at every step: %s); rounding bound %.1e\n",
              a.steps, dt, a.largest, a.identical ? "yes" : "no", rounding_bound(steps * dt));
  EXPECT_EQ(a.steps, steps);
  EXPECT_LE(a.largest, rounding_bound(static_cast<double>(steps) * dt));
}

TEST(EquationsLorenz, EveryRungeKuttaMethodRunsThemAsTheCompiledSystem) {
  for (Integrator integrator : {Integrator::Euler, Integrator::Midpoint, Integrator::Rk4, Integrator::Rk4Doubling, Integrator::Rk45}) {
    const Agreement a = lorenz_agreement(integrator, 1000, 1e-3);  // to t = 1
    std::printf("  %-13s %ld steps: largest difference %.3e\n", motus::info(integrator).name, a.steps, a.largest);
    EXPECT_GT(a.steps, 0);
    EXPECT_LE(a.largest, rounding_bound(1.0)) << motus::info(integrator).name;
  }
}

TEST(EquationsLorenz, TheSymplecticMethodsAreRefused) {
  const auto scene = motus::load_scene(scene_path("lorenz_equations"));
  try {
    motus::Simulation sim(scene, Integrator::VelocityVerlet);
    FAIL() << "a symplectic integrator ran a first-order system";
  } catch (const motus::SceneError& e) {
    EXPECT_EQ(e.field(), "integrator");
  }
}

// ---------------------------------------------------------------------------------------------
// Arenstorf: the periodic orbit returns to its start.

TEST(EquationsArenstorf, Rk45AtATightToleranceReturnsToTheStartAtThePeriod) {
  const auto scene = motus::load_scene(scene_path("arenstorf"));
  ASSERT_EQ(scene.reference.size(), 1u);
  const double period = 17.0652165601579625588917206249;  // integrators.md
  EXPECT_DOUBLE_EQ(scene.reference[0].t, period);
  const motus::Vector y0 = Eigen::Map<const motus::Vector>(scene.first_order->initial.data(), 4);
  const motus::Vector reference = Eigen::Map<const motus::Vector>(scene.reference[0].state.data(), 4);
  EXPECT_EQ(y0, reference);  // the reference state is the start: the orbit is periodic
  EXPECT_DOUBLE_EQ(y0[3], -2.00158510637908252240537862224);

  motus::Simulation sim(scene, Integrator::Rk45);
  sim.advance(period, scene.dt, motus::Tolerance{1e-13, 1e-13});
  const double error = max_difference(sim.state(), y0);
  std::printf("  rk45 at rtol = atol = 1e-13: %ld steps (%ld rejected), %ld evaluations, |y(T) - y0| = %.3e\n",
              sim.steps(), sim.rejected(), sim.evaluations(), error);
  EXPECT_EQ(sim.time(), period);
  EXPECT_LT(error, 1e-8);  // the issue
}

// The order-8 pair on the same orbit: the issue's "new high-order method at a tight tolerance".
TEST(EquationsArenstorf, Dop853AtATightToleranceReturnsToTheStartAtThePeriod) {
  const auto scene = motus::load_scene(scene_path("arenstorf"));
  const double period = scene.reference.at(0).t;
  const motus::Vector y0 = Eigen::Map<const motus::Vector>(scene.first_order->initial.data(), 4);
  motus::Simulation sim(scene, Integrator::Dop853);
  sim.advance(period, scene.dt, motus::Tolerance{1e-13, 1e-13});
  const double error = max_difference(sim.state(), y0);
  std::printf("  dop853 at rtol = atol = 1e-13: %ld steps (%ld rejected), %ld evaluations, |y(T) - y0| = %.3e\n",
              sim.steps(), sim.rejected(), sim.evaluations(), error);
  EXPECT_EQ(sim.time(), period);  // an adaptive run lands on the end time exactly
  EXPECT_LT(error, 1e-8);
}

// ---------------------------------------------------------------------------------------------
// Van der Pol: the period of the limit cycle.

// Times where x crosses 0 upwards, each placed inside its step by the cubic Hermite interpolant
// of x (values and slopes at both ends of the step), whose error is O(h^4).
std::vector<double> upward_zero_crossings(const motus::SceneDescription& scene, Integrator integrator, double h, double end) {
  motus::Simulation sim(scene, integrator);
  auto& f = *sim.first_order_system();
  motus::Vector previous = sim.state(), slope_before(2), slope_after(2);
  double t_previous = sim.time();
  std::vector<double> crossings;
  sim.advance(end, h, motus::Tolerance{1e-12, 1e-12}, [&](const motus::Simulation& s) {
    const motus::Vector& now = s.state();
    if (previous[0] < 0 && now[0] >= 0) {
      f.derivative(t_previous, previous, slope_before);
      f.derivative(s.time(), now, slope_after);
      const double step = s.time() - t_previous;
      auto x = [&](double u) {  // u in [0, 1] across the step
        const double h00 = (1 + 2 * u) * (1 - u) * (1 - u), h10 = u * (1 - u) * (1 - u), h01 = u * u * (3 - 2 * u),
                     h11 = u * u * (u - 1);
        return h00 * previous[0] + h10 * step * slope_before[0] + h01 * now[0] + h11 * step * slope_after[0];
      };
      double lo = 0, hi = 1;
      for (int i = 0; i < 100; ++i) {
        const double mid = 0.5 * (lo + hi);
        (x(mid) < 0 ? lo : hi) = mid;
      }
      crossings.push_back(t_previous + 0.5 * (lo + hi) * step);
    }
    previous = now;
    t_previous = s.time();
  });
  return crossings;
}

TEST(EquationsVanDerPol, TheLimitCyclePeriodIsTheReferenceOne) {
  const auto scene = motus::load_scene(scene_path("van_der_pol"));
  EXPECT_EQ(scene.first_order->parameters.at("mu"), 1.0);
  const double reference = 6.6632868593231;  // integrators.md: mu = 1
  // rk4 with h = 1e-3: its phase error ~ h^4 per unit time and the interpolant's ~ h^4 are far
  // below 1e-8; from (2, 0) the orbit is on the cycle to rounding after a few turns.
  const auto crossings = upward_zero_crossings(scene, Integrator::Rk4, 1e-3, 8 * reference);
  ASSERT_GE(crossings.size(), 7u);
  const double period = crossings[6] - crossings[5];
  std::printf("  rk4, h = 1e-3: periods between upward crossings:");
  for (size_t i = 1; i < crossings.size(); ++i) std::printf(" %.13f", crossings[i] - crossings[i - 1]);
  std::printf("\n  period 6 - 5 = %.13f, reference %.13f, difference %.2e\n", period, reference, period - reference);
  EXPECT_NEAR(period, reference, 1e-8);  // the issue
}

// ---------------------------------------------------------------------------------------------
// Bad equations: one SceneFileError naming the field (and the column where one applies).

struct BadEquations {
  const char* name;
  std::string system;  // the "system" object's members after "type"
  std::string field;
  std::string what;
};

const std::vector<BadEquations> kBad = {
    {"unknown_variable", R"j("variables": ["x", "v"], "equations": {"x": "v", "v": "-k*x"}, "initial": [1, 0])j",
     "system.equations.v", "unknown variable \"k\" at column 2"},
    {"syntax_error", R"j("variables": ["x", "v"], "equations": {"x": "v", "v": "-(x +* v)"}, "initial": [1, 0])j",
     "system.equations.v", "syntax error at column 6"},
    {"missing_parenthesis", R"j("variables": ["x"], "equations": {"x": "sin(x"}, "initial": [1])j", "system.equations.x",
     "syntax error at column 6: missing parenthesis"},
    {"missing_equation", R"j("variables": ["x", "v"], "equations": {"x": "v"}, "initial": [1, 0])j", "system.equations.v",
     "missing: every variable needs its equation"},
    {"extra_equation", R"j("variables": ["x", "v"], "equations": {"x": "v", "v": "-x", "w": "1"}, "initial": [1, 0])j",
     "system.equations.w", "no variable is called \"w\""},
    {"two_expressions", R"j("variables": ["x"], "equations": {"x": "x, 2"}, "initial": [1])j", "system.equations.x",
     "is 2 expressions (a ',' at column 2)"},
    {"assignment", R"j("variables": ["x", "v"], "equations": {"x": "v = 2", "v": "-x"}, "initial": [1, 0])j",
     "system.equations.x", "an assignment at column 3"},
    {"empty_equation", R"j("variables": ["x"], "equations": {"x": "  "}, "initial": [1])j", "system.equations.x", "is empty"},
    {"equation_not_a_string", R"j("variables": ["x"], "equations": {"x": 3}, "initial": [1])j", "system.equations.x",
     "must be a string"},
    {"variable_named_t", R"j("variables": ["t"], "equations": {"t": "1"}, "initial": [1])j", "system.variables[0]",
     "is the time"},
    {"variable_named_like_a_function", R"j("variables": ["x", "exp"], "equations": {"x": "1", "exp": "1"}, "initial": [1, 0])j",
     "system.variables[1]", "is one of the functions"},
    {"bad_variable_name", R"j("variables": ["2x"], "equations": {"2x": "1"}, "initial": [1])j", "system.variables[0]",
     "is not a name"},
    {"repeated_variable", R"j("variables": ["x", "x"], "equations": {"x": "1"}, "initial": [1, 0])j", "system.variables[1]",
     "listed twice"},
    {"parameter_named_like_a_variable",
     R"j("variables": ["x"], "parameters": {"x": 1}, "equations": {"x": "1"}, "initial": [1])j", "system.parameters.x",
     "is a variable"},
    {"parameter_not_a_number", R"j("variables": ["x"], "parameters": {"k": "one"}, "equations": {"x": "k"}, "initial": [1])j",
     "system.parameters.k", "must be a number"},
    {"no_variables", R"j("variables": [], "equations": {}, "initial": [])j", "system.variables", "at least one"},
    {"missing_equations", R"j("variables": ["x"], "initial": [1])j", "system.equations", "missing (required)"},
    {"wrong_initial_length", R"j("variables": ["x", "v"], "equations": {"x": "v", "v": "-x"}, "initial": [1])j",
     "system.initial", "must have 2 numbers (got 1)"},
    {"unknown_system_field", R"j("variables": ["x"], "equations": {"x": "1"}, "initial": [1], "equation": {})j",
     "system.equation", "unknown field"},
    // muparser reads up to a NUL: the rest, "*1000 + k", was dropped unseen, and the run went on.
    {"nul_inside", R"j("variables": ["x", "v"], "equations": {"x": "v\u0000*1000 + k", "v": "-x"}, "initial": [1, 0])j",
     "system.equations.x", "a control character (code 0) at column 2"},
    // A number out of range or cut short is no unknown variable; the symbol named is the word at
    // the column, not the rest of the expression; muparser's own position is not named twice.
    {"number_out_of_range", R"j("variables": ["x"], "equations": {"x": "1e309 * x"}, "initial": [1])j",
     "system.equations.x", "not a number at column 1: \"1e309\""},
    {"number_cut_short", R"j("variables": ["x"], "equations": {"x": "1.5e"}, "initial": [1])j", "system.equations.x",
     "not a number at column 1: \"1.5e\""},
    {"no_operator", R"j("variables": ["x"], "equations": {"x": "3 % x"}, "initial": [1])j", "system.equations.x",
     "syntax error at column 3: \"%\" is no operator, number or name"},
    {"not_ascii", R"j("variables": ["x"], "equations": {"x": "μ*x"}, "initial": [1])j", "system.equations.x",
     "syntax error at column 1: \"μ\" is no operator"},
    {"unknown_variable_then_more", R"j("variables": ["x"], "equations": {"x": "x + k2_ * x"}, "initial": [1])j",
     "system.equations.x", "unknown variable \"k2_\" at column 5 (known"},
    {"too_few_arguments", R"j("variables": ["x"], "equations": {"x": "sum()"}, "initial": [1])j", "system.equations.x",
     "syntax error at column 6: too few parameters for function \"sum\""},
};

class BadEquationsTest : public ::testing::TestWithParam<BadEquations> {};

TEST_P(BadEquationsTest, OneErrorNamingTheField) {
  const auto& c = GetParam();
  const std::string text = R"j({"system": {"type": "equations", )j" + c.system + R"j(}, "dt": 0.1, "duration": 1})j";
  try {
    motus::parse_scene(text, "bad.json");
    FAIL() << "accepted: " << text;
  } catch (const motus::SceneFileError& e) {
    EXPECT_EQ(e.field, c.field) << e.what();
    EXPECT_NE(e.message.find(c.what), std::string::npos) << "expected: " << c.what << "\ngot: " << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    EXPECT_EQ(e.message.find("position"), std::string::npos) << e.what();  // (a column is named once, ours)
  }
}

INSTANTIATE_TEST_SUITE_P(Loader, BadEquationsTest, ::testing::ValuesIn(kBad),
                         [](const auto& info) { return std::string(info.param.name); });

// --set reaches the parameters and the equations, as for every other field.
TEST(EquationsLoader, SetChangesParametersAndEquations) {
  const auto scene = motus::load_scene(scene_path("van_der_pol"),
                                       {"system.parameters.mu=2.5", "system.equations.v=mu*(1 - x*x)*v - x"});
  EXPECT_EQ(scene.first_order->parameters.at("mu"), 2.5);
  motus::Simulation sim(scene, Integrator::Rk4);
  motus::Vector dydt(2);
  motus::Vector y(2);
  y << 0.5, 1;
  sim.first_order_system()->derivative(0, y, dydt);
  EXPECT_EQ(dydt[0], 1.0);
  EXPECT_DOUBLE_EQ(dydt[1], 2.5 * (1 - 0.25) * 1 - 0.5);
  EXPECT_EQ(sim.state_names(), (std::vector<std::string>{"x", "v"}));
}

// An adaptive step whose error estimate is NaN (the state is no longer a number) is rejected, never
// taken: the run stops with the state still finite, before t = 0.3, where the right-hand side
// stops being a number. (Accepted, a NaN step size followed, and t = nan in the message.)
TEST(EquationsLoader, AnAdaptiveStepIntoNaNIsRejected) {
  const auto scene = motus::parse_scene(
      R"j({"system": {"type": "equations", "variables": ["x"], "equations": {"x": "t > 0.3 ? sqrt(-1) : 1"},
          "initial": [0]}, "dt": 0.1, "duration": 1})j",
      "nan.json");
  for (const Integrator integrator : {Integrator::Rk45, Integrator::Dop853, Integrator::Rk4Doubling}) {
    motus::Simulation sim(scene, integrator);
    try {
      sim.advance(1, 0.1, {1e-6, 1e-6});
      ADD_FAILURE() << motus::info(integrator).name << " ran through";
    } catch (const std::runtime_error& e) {
      // (It names the equation that gave the NaN, within the rejected step, past t = 0.3.)
      EXPECT_NE(std::string(e.what()).find("rejected step at t = "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("the equation x' = t > 0.3 ? sqrt(-1) : 1 gave nan at t = 0."), std::string::npos)
          << e.what();
    }
    EXPECT_TRUE(std::isfinite(sim.state()[0])) << motus::info(integrator).name;
    EXPECT_LE(sim.time(), 0.3) << motus::info(integrator).name;
    EXPECT_NEAR(sim.state()[0], sim.time(), 1e-12) << motus::info(integrator).name;  // x = t until then
  }
}

// A run whose state stops being finite names the equation that made it so, when one gave a NaN
// (or an infinity) from a moderate state: x' = sqrt(x - 2) from x = 1 is outside the square
// root's domain at once. A run that blows up through ever larger numbers (x' = x², whose exact
// solution 1/(1 − t) is infinite at t = 1) names none: its step is to blame, not its equation.
TEST(EquationsLoader, AnEquationThatGivesNaNFromAModerateStateIsNamedAndABlowUpIsNot) {
  const auto domain = motus::parse_scene(
      R"j({"system": {"type": "equations", "variables": ["x", "v"], "equations": {"x": "v", "v": "sqrt(x - 2)"},
          "initial": [1, 0.5]}, "dt": 0.1, "duration": 1})j",
      "domain.json");
  motus::Simulation sim(domain, Integrator::Rk4);
  sim.advance(1, 0.1, {});
  EXPECT_FALSE(sim.state().allFinite());
  EXPECT_EQ(sim.first_order_system()->why_not_finite(),
            "the equation v' = sqrt(x - 2) gave nan at t = 0 where x = 1, v = 0.5 (outside a function's domain? a "
            "division by zero?)");
  const auto blow_up = motus::parse_scene(
      R"j({"system": {"type": "equations", "variables": ["x"], "equations": {"x": "x * x"}, "initial": [1]},
          "dt": 0.1, "duration": 3})j",
      "blow_up.json");
  motus::Simulation runaway(blow_up, Integrator::Rk4);
  runaway.advance(3, 0.1, {});
  EXPECT_FALSE(runaway.state().allFinite());
  EXPECT_EQ(runaway.first_order_system()->why_not_finite(), "");
}

// t is the time: a forced system sees it.
TEST(EquationsLoader, TheTimeIsT) {
  const auto scene = motus::parse_scene(
      R"j({"system": {"type": "equations", "variables": ["x"], "equations": {"x": "cos(t)"}, "initial": [0]},
          "dt": 0.001, "duration": 1})j",
      "forced.json");
  motus::Simulation sim(scene, Integrator::Rk4);
  sim.advance(1, 1e-3, {});
  EXPECT_NEAR(sim.state()[0], std::sin(1.0), 1e-12);  // x = sin t; rk4's error ~ h^4
}

}  // namespace
