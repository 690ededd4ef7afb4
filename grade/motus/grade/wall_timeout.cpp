// Whether the machine was too busy, or the code too slow: the judgement of a wall-clock time-out, the
// wait for a core it rests on, and the grader's message when the machine is to blame.
#include "motus/grade/wall_timeout.hpp"

#include <sched.h>
#include <unistd.h>

#include <algorithm>

#include "motus/grade/format_seconds.hpp"

namespace motus::grade {

using detail::format_seconds;

double waited_for_a_core(const TaskWaits& waits) {
  std::unordered_map<pid_t, double> longest;  // by process
  for (const auto& [task, wait] : waits) longest[wait.process] = std::max(longest[wait.process], wait.delay);
  double sum = 0;
  for (const auto& [process, delay] : longest) sum += delay;
  return sum;
}

int available_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (::sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  const long online = ::sysconf(_SC_NPROCESSORS_ONLN);
  return online > 0 ? static_cast<int>(online) : 1;
}

std::string starved_message(const std::string& what, const TimeUse& use, double cpu_limit) {
  const int cores = available_cores();
  std::string got = "in " + format_seconds(use.wall) + " s it had " + format_seconds(use.cpu) + " s of CPU";
  if (use.run_delay_known) got += " and waited " + format_seconds(use.run_delay) + " s for a core";
  return "the machine was too busy to give " + what + " its " + format_seconds(cpu_limit) + " s of CPU (" + got +
         "): not the submission's fault; grade it again with fewer --jobs (this machine has " + std::to_string(cores) +
         " core" + (cores == 1 ? "" : "s") + ") or when the machine is less busy";
}

WallVerdict judge_wall_timeout(const TimeUse& use, double cpu_limit) {
  if (use.cpu >= cpu_limit) return WallVerdict::used_its_cpu;
  if (use.lowered_priority) return WallVerdict::lowered_its_priority;
  const double idle = std::max(0.0, use.wall - use.cpu);  // the time it did not compute
  const double waited_for_a_core = use.run_delay_known ? use.run_delay : use.runnable_now ? idle : 0;
  return use.wall > 0 && use.cpu + waited_for_a_core >= kStarvedShare * use.wall ? WallVerdict::starved : WallVerdict::waiting;
}

}  // namespace motus::grade
