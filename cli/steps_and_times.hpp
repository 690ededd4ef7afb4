#pragma once
// A run's fixed steps and what they can resolve: how many steps a duration takes, and whether the
// times and the positions can be told apart at the step; and what the scene's time is counted in.
#include <string>

#include "motus/scene.hpp"

namespace motus::cli {

// The most fixed steps a run may take: beyond this a step count is not a number to count in
// (and t0 + i·dt is no longer exact in double precision).
constexpr double kMaxSteps = 1e15;
// The number of fixed steps of dt that `duration` takes; InputError naming `what` when it is
// not a number of steps one could count.
long checked_step_count(double duration, double dt, const std::string& what);
// Refuses a mechanical scene so far from the origin that its positions cannot take its moves at the
// step `dt` a command runs (exit 2), naming the field that puts its bodies there: at 1e17 m doubles
// are 16 m apart, and a ball at 1 m/s with dt = 0.01 never moved, exit 0. The rule, and the field
// named (a body's position, a generator's origin or spacing, a wall's offset or corner), are
// coarse_resolution's (motus/scene_file/scene_file.hpp): the moves, a body's speed times dt at the
// start or after the scene's duration under the forces at the start, must be at least a thousand times
// the positions' spacing where the bodies are. With contacts, where a step takes the bodies doubles
// must also be at most a thousandth of the smallest radius apart (coarse_resolution), else
// `dt_what` ("--dt", or "FILE: dt") is named: at dt = 1e16 s two balls of 0.5 m met head-on and kept
// their velocities, exit 0.
void check_position_resolution(const SceneDescription& scene, double dt, const std::string& path, const std::string& dt_what);
// Refuses a run whose times cannot be told apart at its step (exit 2), naming start_what when
// start_time is what takes the run far from 0, else step_what (dt, the duration or the option).
void check_time_resolution(double start_time, double duration, double dt, const std::string& start_what,
                           const std::string& step_what);

// What the scene's time is counted in, for people: "s", or "years" for World2 (the system
// catalog's time_unit).
std::string time_unit_of(const SceneDescription& scene);

}  // namespace motus::cli
