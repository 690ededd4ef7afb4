#pragma once
// How busy the machine is: its load average and the cores it has online, taken as timings begin
// and end (on a busy machine the ratios may be off).

namespace motus::cli {

// The 1-minute load average: the first number of /proc/loadavg — or of the file MOTUS_LOADAVG
// names, the tests' way to make the machine look busy or idle; NaN when it cannot be read.
double load_average();
// The cores the machine has online (as the grader counts them), or 0 when it does not say.
long online_cores();

}  // namespace motus::cli
