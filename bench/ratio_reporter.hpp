#pragma once
// Google Benchmark's console output, plus ratios between benchmarks of the same run
// (speed claims are ratios measured side by side, never absolute times).
//
// Times are CPU time (what Google Benchmark measures for the process besides wall time), so
// that time the process spends waiting for a core on a busy machine is not counted — or, for a
// benchmark that times itself (UseManualTime), the time it measured. With
// repetitions (bench_constraints runs 5 by default, interleaved in a random order, through
// initialize() below; the other programs when given --benchmark_repetitions=5
// --benchmark_enable_random_interleaving=true), each benchmark shows its mean, median, standard
// deviation and coefficient of variation over them, and its minimum where the benchmark registers
// it (with_min, or ->ComputeStatistics("min", minimum)); each ratio is taken between the fastest
// repetitions, with the ratio of the medians beside it. A benchmark whose repetitions the reporter
// did not see one by one (--benchmark_display_aggregates_only=true) and that has no "min"
// statistic has no fastest repetition: its median then stands in for it, and its ratios say so.
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
  // CPU ns per iteration of each benchmark: every repetition, and the aggregates "min" and
  // "median" when there were repetitions.
  std::map<std::string, std::vector<double>> ns_per_iteration_;
  std::map<std::string, double> min_, median_;
  struct Ratio {
    std::string label, numerator, denominator;
    double numerator_per;
  };
  std::vector<Ratio> ratios_;
};

// benchmark::Initialize with motus's defaults for what the command line does not set: 5
// repetitions, interleaved in a random order, only the aggregates (and each ratio) printed.
void initialize(int* argc, char** argv);

// The minimum of a benchmark's repetitions, for ->ComputeStatistics("min", minimum) (the fastest
// repetition, which the ratios use).
double minimum(const std::vector<double>& v);

// Adds the minimum over the repetitions to a benchmark's statistics (of its times and counters).
benchmark::internal::Benchmark* with_min(benchmark::internal::Benchmark* b);

}  // namespace motus::bench
