#pragma once
// Why a sandboxed process hit the wall-clock backstop (sandbox.hpp's wall_backstop): the code too
// slow or waiting (the student's), or the machine too busy to give it its CPU (the grader's failure,
// MachineTooBusy) — judged from what the process did with its time.
#include <sys/types.h>

#include <stdexcept>
#include <string>
#include <unordered_map>

namespace motus::grade {

// What a sandboxed process tree (bubblewrap and every process under it) did with its time,
// measured just before it is killed at its deadline.
struct TimeUse {
  double wall = 0;       // seconds since it started
  double cpu = 0;        // seconds of CPU it used (user and system, with its reaped children's)
  double run_delay = 0;  // seconds it waited for a core, runnable (/proc/…/schedstat; waited_for_a_core)
  bool run_delay_known = false;  // false: no schedstat on this kernel
  bool runnable_now = false;     // one of its threads was runnable (state R) when measured
  bool lowered_priority = false; // it made itself nicer than the grader, or SCHED_IDLE
};

// A task's (a thread's) wait for a core as last seen (/proc/…/schedstat's run_delay, s), and the
// process it is in; TaskWaits holds them by task id.
struct TaskWait {
  pid_t process = 0;
  double delay = 0;
};
using TaskWaits = std::unordered_map<pid_t, TaskWait>;

// How long a process tree waited for a core: each process's longest wait of one of its threads,
// summed over its processes. A process's threads are not summed: threads waiting for each other's
// cores are the code's own doing, not a busy machine's (a submission of 50 threads that woke
// together every 0.5 s for 0.5 ms of work each, 0.4 s of CPU in 9 s, summed 24.4 s of waits and
// was called starved: the grader's failure, where it is the student's time-out). Processes one
// after another (a compile: g++, cc1plus, as) each wait their own.
double waited_for_a_core(const TaskWaits& waits);

// Why the wall-clock backstop fired, from what the process did (a pure function of its numbers):
// - used_its_cpu: it used `cpu_limit` seconds of CPU or more (too slow: the student's);
// - lowered_its_priority: it asked to run only when nothing else wants to (nice, SCHED_IDLE) and
//   was not run (the student's doing);
// - starved: it was runnable for most of the wall time — CPU used plus time waiting for a core at
//   least half of it — and used less than its CPU: the machine was too busy (the grader's failure);
// - waiting: it was mostly blocked or asleep (the student's: waiting, not computing).
// Without schedstat the wait for a core is unknown: then the time it did not compute counts as
// waiting for a core if it was runnable when measured, else as blocked.
enum class WallVerdict { used_its_cpu, lowered_its_priority, starved, waiting };
WallVerdict judge_wall_timeout(const TimeUse& use, double cpu_limit);
// The share of the wall time a process must have been runnable to count as starved.
constexpr double kStarvedShare = 0.5;

// The cores this process may run on (its CPU affinity; at least 1).
int available_cores();
// The grader's failure when `what` ("the compiler", "the test euler.table") was starved: one
// sentence with what it got in its wall time, and what to do (fewer --jobs).
std::string starved_message(const std::string& what, const TimeUse& use, double cpu_limit);

// A test or a build that the machine did not give its CPU (WallVerdict::starved): the grader's
// failure, never the student's. (Not a ProbeFailure: it ends the grading, exit 1.)
class MachineTooBusy : public std::runtime_error {
public:
  explicit MachineTooBusy(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace motus::grade
