#pragma once
// The run folder of `motus bench precision` (docs/cli.md): precision.csv (every point of every
// curve), targets.csv (every curve read at every target error), the two work–precision diagrams —
// error against run time and error against derivative evaluations, log–log, one line per method,
// PNG and SVG drawn by gnuplot (plot/) — and index.html with the table of the fastest methods.
#include <string>
#include <vector>

#include "motus/precision/work_precision.hpp"

namespace motus::precision {

struct ReportContext {
  std::string scene, file, description;
  double start = 0, end = 0;
  std::string time_unit = "s";  // the scene's simulated time ("years" for World2), for start, end and dt
  Sweep sweep;
  std::vector<double> targets;
  std::vector<std::string> versions;  // one line per engine taking part ("Boost.Odeint, Boost 1.74.0")
  // The machine's load while the points were timed (compare::machine_load_sentence), and the warning
  // when it was busier than its cores, or "".
  std::string machine_load, busy_machine;
};

// The CSV of precision.csv, which --csv also writes: a header and one row per point.
std::string precision_csv(const std::string& scene, const std::vector<Curve>& curves);

// Writes the folder's files; returns "" or the one line the plots gave (gnuplot missing or failed:
// the rest is written all the same). Throws std::runtime_error when a file cannot be written.
std::string write_precision_report(const std::string& folder, const ReportContext& context,
                                   const std::vector<Curve>& curves);

}  // namespace motus::precision
