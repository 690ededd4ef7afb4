#pragma once
// Parts of a run given from outside the engine as plain functions: an integrator, a
// collision response, a constraint projection. This is how a student's plug-in
// (plugin/, assignments/) puts its own code into every motus command: the engine calls
// these where it would call its own, and knows nothing of plug-ins or shared libraries.
//
// Everything here has a C layout (plain structs, function pointers, double arrays), so it
// crosses a shared-library boundary as it is. Every function returns 0 when it worked, or
// nonzero after keeping a one-line message that error(self) returns; the engine then throws
// ExternalError with it. Arrays of points hold body i's coordinate k at i·d + k.
//
// kExternalPartsVersion changes whenever anything below does.
#include <stdexcept>
#include <string>

namespace motus {

constexpr int kExternalPartsVersion = 1;

// ---- Systems, as an outside integrator sees them -------------------------------------------

// y' = f(t, y), with `size` state variables.
struct ExternalFirstOrder {
  int size;
  void* self;
  void (*derivative)(void* self, double t, const double* y, double* dydt);
};

// x'' = a(t, x, v), with `size` coordinates (bodies × dimensions).
struct ExternalMechanical {
  int size;
  void* self;
  void (*acceleration)(void* self, double t, const double* x, const double* v, double* a);
};

// ---- An integrator ---------------------------------------------------------------------------

enum ExternalIntegratorKind : int {
  kExternalFirstOrder = 0,      // step(f, t, h, y): one step of a fixed size, on any system
  kExternalAdaptive = 1,        // try_step(f, t, &h, y, ...): one attempt; picks its next step
  kExternalMechanical = 2,      // step_mechanical(s, t, h, x, v): one step, on point masses
  kExternalPositionVerlet = 3,  // verlet_start, then verlet_step(s, t, h, x, x_previous)
};

struct ExternalIntegrator {
  const char* name;         // "euler": shown as PLUGIN:NAME ("student:euler")
  const char* description;  // one line
  int order;                // the global order it claims (for listings)
  int kind;                 // an ExternalIntegratorKind
  void* self;
  int (*step)(void* self, const ExternalFirstOrder* f, double t, double h, double* y);
  // On success *accepted says whether the step was kept (then y holds the new state); either
  // way *h becomes the step to try next. The tolerance is atol + rtol·max(|y_i|, |y_new_i|), component
  // by component.
  int (*try_step)(void* self, const ExternalFirstOrder* f, double t, double* h, double* y, double atol, double rtol,
                  int* accepted);
  int (*step_mechanical)(void* self, const ExternalMechanical* s, double t, double h, double* x, double* v);
  // x_{−1} from x_0 and v_0; then one step moves (x_n, x_{n−1}) to (x_{n+1}, x_n). v is the
  // velocity last reported (for forces that depend on it); the method itself keeps none.
  int (*verlet_start)(void* self, const ExternalMechanical* s, double t, double h, const double* x, const double* v,
                      double* x_previous);
  int (*verlet_step)(void* self, const ExternalMechanical* s, double t, double h, double* x, double* x_previous,
                     const double* v);
  const char* (*error)(void* self);
};

// ---- A collision response: what happens when bodies touch, and when they will --------------

struct ExternalCollisionRules {
  void* self;
  // Two balls of masses m_a, m_b meet along the unit normal n (from a to b), restitution e:
  // their velocities v_a, v_b (d numbers each) after the impulse.
  int (*collide_balls)(void* self, int d, double* v_a, double* v_b, double m_a, double m_b, const double* n, double e);
  // A ball meets a static wall whose unit normal n points into the free side: its velocity after.
  int (*bounce_off_wall)(void* self, int d, double* v, const double* n, double e);
  // The first t ≥ 0 at which balls moving on straight lines from p_a, p_b touch
  // (|p_b − p_a + (v_b − v_a) t| = r_a + r_b), else +∞. Touching or overlapping and closing: 0.
  int (*balls_impact)(void* self, int d, const double* p_a, const double* v_a, double r_a, const double* p_b,
                      const double* v_b, double r_b, double* t);
  // The first t ≥ 0 at which a ball of radius r from p with velocity v touches the plane
  // n·x = offset from its free side n·x > offset, else +∞.
  int (*plane_impact)(void* self, int d, const double* p, const double* v, double r, const double* n, double offset,
                      double* t);
  const char* (*error)(void* self);
};

// ---- A constraint projection: sticks, pins and walls on Verlet ------------------------------

struct ExternalStick {
  int a, b;
  double length;
};
struct ExternalPin {
  int body;
  double position[3];
};
struct ExternalWall {  // the free side is n·x ≥ offset, |n| = 1
  double normal[3];
  double offset;
};

// A run's constraints; the arrays stay valid (at the same addresses) for the whole run, and
// `id` is the run's own (no two sets share one), so a projection may prepare once per id.
struct ExternalConstraintSet {
  long id;
  int dimensions, bodies;
  const double* inverse_mass;  // each body's 1/m (pinned bodies too: holding them is the projection's job)
  const double* radius;        // 0 for a point
  int stick_count;
  const ExternalStick* sticks;
  int pin_count;
  const ExternalPin* pins;
  int wall_count;
  const ExternalWall* walls;
  int iterations;  // the scene's constraint_iterations
};

struct ExternalConstraintRules {
  void* self;
  // Moves the positions x (bodies × dimensions numbers) back onto the constraints.
  int (*project)(void* self, const ExternalConstraintSet* set, double* x);
  const char* (*error)(void* self);
};

// ---- What a run takes from outside -----------------------------------------------------------

// Any of these may be null: the engine's own part is used instead.
struct ExternalParts {
  const ExternalCollisionRules* collisions = nullptr;
  const ExternalConstraintRules* constraints = nullptr;
};

// A part from outside failed (its function returned nonzero): what it said.
class ExternalError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// The part's own code failed (it threw: its function returned nonzero), rather than returning
// numbers the engine then refused. The grader tells the two apart: a hint about wrong numbers
// does not help with an exception.
class ExternalCodeFailed : public ExternalError {
public:
  using ExternalError::ExternalError;
};

// Throws ExternalCodeFailed("WHAT: MESSAGE") when status is nonzero.
inline void check_external(int status, const char* what, const char* (*error)(void*), void* self) {
  if (status == 0) return;
  const char* message = error ? error(self) : nullptr;
  throw ExternalCodeFailed(std::string(what) + ": " + (message && *message ? message : "failed"));
}

}  // namespace motus
