#pragma once
// What `motus compare` leaves behind in its folder: the metrics as CSV and JSON, plots
// of energy and momentum against time (matplotlib), and an index.html that opens
// straight from the file system.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "motus/compare/comparison.hpp"

namespace motus::compare {

struct ReportContext {
  std::string scene_name, scene_file, description;
  std::string integrator;
  double dt = 0, duration = 0;
  int dimensions = 2;
  long bodies = 0;
  std::string video, contact_sheet;  // file names in the folder (--render), or ""
};

// The summary of every engine as one JSON object (also what --json prints).
nlohmann::json summary_json(const ReportContext& context, const std::vector<EngineRun>& runs);

// Writes metrics.csv, summary.json, plot.py (+ energy.png, momentum.png when a python3
// with matplotlib is found) and index.html into `folder` (which must exist). Returns a
// line to show the user when the plots could not be made, else an empty string.
std::string write_report(const std::string& folder, const ReportContext& context, const std::vector<EngineRun>& runs);

// The python3 that has matplotlib (Debian's /usr/bin/python3 first: the first python3 on
// PATH may be an interpreter without Debian's packages), or "" when there is none.
std::string python_with_matplotlib();

}  // namespace motus::compare
