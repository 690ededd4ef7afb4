#include "ratio_reporter.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace motus::bench {
namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

void RatioReporter::add_ratio(std::string label, std::string numerator, std::string denominator,
                              double numerator_per) {
  ratios_.push_back({std::move(label), std::move(numerator), std::move(denominator), numerator_per});
}

void RatioReporter::ReportRuns(const std::vector<Run>& runs) {
  for (const auto& run : runs) {
    if (run.error_occurred) continue;
    // A benchmark that times itself (UseManualTime: the gas times only its steps, in thread CPU
    // time, not the fresh gas it builds each iteration) reports that time as its real time.
    const bool manual = run.run_name.time_type == "manual_time";
    const double seconds = manual ? run.GetAdjustedRealTime() : run.GetAdjustedCPUTime();
    const double ns = seconds * benchmark::GetTimeUnitMultiplier(run.time_unit) * 1e9;
    if (run.run_type == Run::RT_Iteration) ns_per_iteration_[run.run_name.str()].push_back(ns);
    if (run.run_type == Run::RT_Aggregate && run.aggregate_name == "min") min_[run.run_name.str()] = ns;
    if (run.run_type == Run::RT_Aggregate && run.aggregate_name == "median") median_[run.run_name.str()] = ns;
  }
  ConsoleReporter::ReportRuns(runs);
}

void RatioReporter::Finalize() {
  ConsoleReporter::Finalize();
  if (ratios_.empty()) return;
  std::printf("\nratios (same run, CPU time: the fastest repetitions, the medians' ratio beside it):\n");
  // The fastest and the median repetition of a benchmark (0: it did not run), and whether the
  // fastest is known (false: only the median was reported, and it stands in for the fastest).
  struct Times {
    double fastest = 0, median = 0;
    bool fastest_known = true;
  };
  auto times = [&](const std::string& name) -> Times {
    if (min_.count(name) && median_.count(name)) return {min_.at(name), median_.at(name)};
    const auto it = ns_per_iteration_.find(name);
    if (it == ns_per_iteration_.end() || it->second.empty())
      return median_.count(name) ? Times{median_.at(name), median_.at(name), false} : Times{};
    return {*std::min_element(it->second.begin(), it->second.end()), median(it->second)};
  };
  for (const auto& r : ratios_) {
    const Times a = times(r.numerator), b = times(r.denominator);
    if (a.fastest <= 0 || b.fastest <= 0) continue;  // filtered out
    const double fastest = a.fastest / r.numerator_per / b.fastest;
    const double medians = a.median / r.numerator_per / b.median;
    std::printf("  %-62s %7.3fx  (median %.3fx; %s / %s)%s\n", r.label.c_str(), fastest, medians, r.numerator.c_str(),
                r.denominator.c_str(),
                a.fastest_known && b.fastest_known ? "" : "  [no \"min\" statistic: a median stands in for the fastest]");
  }
}

double minimum(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

benchmark::internal::Benchmark* with_min(benchmark::internal::Benchmark* b) { return b->ComputeStatistics("min", minimum); }

void initialize(int* argc, char** argv) {
  static std::vector<char*> args;
  static char repetitions[] = "--benchmark_repetitions=5";
  static char interleaving[] = "--benchmark_enable_random_interleaving=true";
  static char aggregates[] = "--benchmark_display_aggregates_only=true";
  args.assign(argv, argv + *argc);
  auto given = [&](const char* flag) {
    for (int i = 1; i < *argc; ++i)
      if (std::strncmp(argv[i], flag, std::strlen(flag)) == 0) return true;
    return false;
  };
  if (!given("--benchmark_repetitions")) args.push_back(repetitions);
  if (!given("--benchmark_enable_random_interleaving")) args.push_back(interleaving);
  if (!given("--benchmark_display_aggregates_only")) args.push_back(aggregates);
  args.push_back(nullptr);
  *argc = static_cast<int>(args.size()) - 1;
  benchmark::Initialize(argc, args.data());
}

}  // namespace motus::bench
