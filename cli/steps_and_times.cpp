#include "steps_and_times.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "motus/scene_file/scene_file.hpp"
#include "motus/simulation.hpp"
#include "motus/systems/system_catalog.hpp"

namespace motus::cli {

long checked_step_count(double duration, double dt, const std::string& what) {
  const double steps = duration / dt;
  if (!(steps <= kMaxSteps))
    throw InputError(what + ": " + fmt::format("{:g}", steps) + " steps of " + fmt::format("{:g}", dt) +
                     " is more than a run can take (at most " + fmt::format("{:g}", kMaxSteps) + ")");
  // A duration this small against dt cannot be told from the rounding of a time (which takes no
  // step), so it would be run as no step at all.
  if (steps < 1e-9)
    throw InputError(what + ": dt = " + fmt::format("{:g}", dt) + " is more than 10^9 times the duration (" +
                     fmt::format("{:g}", duration) + "): the run would take no step");
  return fixed_step_count(duration, dt);
}

void check_position_resolution(const SceneDescription& scene, double dt, const std::string& path, const std::string& dt_what) {
  const CoarseResolution coarse = coarse_resolution(scene, dt);
  if (coarse.positions) throw InputError(path + ": " + coarse.positions->field() + ": " + coarse.positions->what());
  if (coarse.contacts) throw InputError(dt_what + ": " + *coarse.contacts);
}

void check_time_resolution(double start_time, double duration, double dt, const std::string& start_what,
                           const std::string& step_what) {
  // The times t0 + i·dt must be told apart: far from 0 doubles are too coarse (at 1e17 they are
  // 16 apart), and the steps would land on the wrong times or on the same one. The field to
  // blame is start_time when it is what takes the run far from 0, else dt (or the duration).
  const double end = start_time + duration;
  const double far = std::max(std::abs(start_time), std::abs(end));
  const double spacing = std::nextafter(far, INFINITY) - far;
  if (spacing <= 1e-6 * dt) return;
  const double at = std::abs(start_time) > std::abs(end) ? start_time : end;  // (with its sign: t = -1e308)
  const std::string coarse = "at t = " + fmt::format("{:g}", at) + " times are " + fmt::format("{:g}", spacing) +
                             " apart, too coarse for steps of " + fmt::format("{:g}", dt);
  if (std::abs(start_time) > duration) throw InputError(start_what + ": " + coarse + " (start nearer t = 0)");
  // (With --steps, dt scales the times and their spacing alike: only the count can change. From
  // t = 0 the times are told apart up to the end of the largest binade [2^e, 2^(e+1)) whose spacing
  // 2^(e-52) is at most 1e-6·dt: between 1e-6·2^52 ≈ 4.5e9 and twice that many steps, by where dt
  // falls between two powers of two — 2^33 − 1 at dt = 1.)
  if (step_what == "--steps") {
    const int e = std::ilogb(1e-6 * dt) + 52;
    const double most = std::ceil(std::ldexp(1.0, e + 1) / dt) - 1;
    // A dt so small that no count of steps holds (a subnormal one: doubles near 0 are 4.9e-324 apart,
    // more than a millionth of it) said "at most -1 of 9.99989e-321".
    if (!(most >= 1)) {
      const double least = 1e6 * std::numeric_limits<double>::denorm_min();
      throw InputError(fmt::format("{}: {} (no count of steps that small can be told apart: dt must be at least {:.3g})",
                                   step_what, coarse, least));
    }
    throw InputError(fmt::format("{}: {} (fewer steps: from t = 0, at most {:.3g} of {:g})", step_what, coarse, most, dt));
  }
  throw InputError(step_what + ": " + coarse + " (a larger dt or a shorter duration)");
}

std::string time_unit_of(const SceneDescription& scene) {
  if (scene.first_order)
    if (const auto* info = find_first_order_system(scene.first_order->type); info && info->time_unit == "year")
      return "years";
  return "s";
}

}  // namespace motus::cli
