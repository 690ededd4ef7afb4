#pragma once
// Google Benchmark's console output, plus ratios between benchmarks of the same run
// (speed claims are ratios measured side by side, never absolute times).
#include <benchmark/benchmark.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace motus::bench {

class RatioReporter : public benchmark::ConsoleReporter {
public:
  // After the run, print (time(numerator) / numerator_per) / time(denominator) with a
  // label; numerator_per is how many of the denominator's units one numerator
  // iteration does (e.g. 1000 steps).
  void add_ratio(std::string label, std::string numerator, std::string denominator, double numerator_per = 1);
  void ReportRuns(const std::vector<Run>& runs) override;
  void Finalize() override;

private:
  std::map<std::string, double> ns_per_iteration_;
  struct Ratio {
    std::string label, numerator, denominator;
    double numerator_per;
  };
  std::vector<Ratio> ratios_;
};

}  // namespace motus::bench
