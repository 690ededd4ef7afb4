#include "machine_load.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

namespace motus::cli {

double load_average() {
  const char* file = std::getenv("MOTUS_LOADAVG");
  std::ifstream in(file && *file ? file : "/proc/loadavg");
  double load = NAN;
  return in >> load ? load : NAN;
}

long online_cores() {
  const long cores = ::sysconf(_SC_NPROCESSORS_ONLN);
  return cores > 0 ? cores : 0;
}

}  // namespace motus::cli
