#include "ratio_reporter.hpp"

#include <cstdio>

namespace motus::bench {

void RatioReporter::add_ratio(std::string label, std::string numerator, std::string denominator,
                              double numerator_per) {
  ratios_.push_back({std::move(label), std::move(numerator), std::move(denominator), numerator_per});
}

void RatioReporter::ReportRuns(const std::vector<Run>& runs) {
  for (const auto& run : runs)
    if (!run.error_occurred)  // (aggregates too: "name_median" and the like, for ratios of them)
      ns_per_iteration_[run.benchmark_name()] = run.GetAdjustedRealTime() * benchmark::GetTimeUnitMultiplier(run.time_unit) * 1e9;
  ConsoleReporter::ReportRuns(runs);
}

void RatioReporter::Finalize() {
  ConsoleReporter::Finalize();
  if (ratios_.empty()) return;
  std::printf("\nratios (same run):\n");
  for (const auto& r : ratios_) {
    const auto a = ns_per_iteration_.find(r.numerator), b = ns_per_iteration_.find(r.denominator);
    if (a == ns_per_iteration_.end() || b == ns_per_iteration_.end()) continue;  // filtered out
    std::printf("  %-58s %6.3fx  (%s / %s)\n", r.label.c_str(), a->second / r.numerator_per / b->second, r.numerator.c_str(),
                r.denominator.c_str());
  }
}

}  // namespace motus::bench
