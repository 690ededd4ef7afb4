// README.md's ten-minute tour tells a new user what each command prints; this runs every command
// of the tour (the ```sh blocks of "## A ten-minute tour") and checks that the output shown
// beside it (the ```text block after it) is what the command prints now — line by line, blanks
// collapsed, "…" standing for what varies (run times) or is left out. So the figures the README
// quotes (the notes' six rows, Euler's ×147, the cradle in three engines, RK4 against symplectic
// Euler) come from the command shown, not from an old run.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "cli_harness.hpp"

namespace {

using namespace motus_test;

struct TourStep {
  std::string command;
  std::vector<std::string> shown;  // the lines of the ```text block after it
};

std::string collapse_blanks(const std::string& line) {
  std::string out;
  std::istringstream words(line);
  for (std::string w; words >> w;) out += (out.empty() ? "" : " ") + w;
  return out;
}

std::vector<TourStep> tour() {
  std::ifstream in(MOTUS_SOURCE_DIR "/README.md");
  std::vector<TourStep> steps;
  std::string line, block;
  bool inside = false;
  std::vector<std::string> lines;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0) {
      if (inside) break;
      inside = line == "## A ten-minute tour";
      continue;
    }
    if (!inside) continue;
    if (block.empty() && (line == "```sh" || line == "```text")) {
      block = line.substr(3);
      lines.clear();
    } else if (!block.empty() && line == "```") {
      if (block == "sh") {
        EXPECT_EQ(lines.size(), 1u) << "one command per block";
        steps.push_back({lines.empty() ? "" : lines.front(), {}});
      } else if (!steps.empty() && steps.back().shown.empty()) {
        steps.back().shown = lines;
      }
      block.clear();
    } else if (!block.empty()) {
      lines.push_back(line);
    }
  }
  return steps;
}

// An output line that the shown line describes: equal with blanks collapsed, or — where the shown
// line has "…" — starting with the part before it and holding the parts after it, in order.
bool printed(const std::string& out, const std::string& shown) {
  std::vector<std::string> parts;
  for (size_t from = 0;;) {
    const size_t at = shown.find("…", from);
    parts.push_back(collapse_blanks(shown.substr(from, at == std::string::npos ? std::string::npos : at - from)));
    if (at == std::string::npos) break;
    from = at + std::string("…").size();
  }
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    const std::string l = collapse_blanks(line);
    if (parts.size() == 1) {
      if (l == parts[0]) return true;
      continue;
    }
    if (l.rfind(parts[0], 0) != 0) continue;
    size_t at = parts[0].size();
    bool all = true;
    for (size_t k = 1; k < parts.size() && all; ++k) {
      if (parts[k].empty()) continue;
      const size_t found = l.find(parts[k], at);
      all = found != std::string::npos;
      if (all) at = found + parts[k].size();
    }
    if (all) return true;
  }
  return false;
}

TEST(Readme, TheTourHasItsFourSteps) {
  const auto steps = tour();
  ASSERT_GE(steps.size(), 5u);
  for (const auto& s : steps) {
    EXPECT_EQ(s.command.rfind("build/motus ", 0), 0u) << s.command;
    EXPECT_FALSE(s.shown.empty()) << "no output shown for " << s.command;
  }
}

TEST(Readme, EveryTourCommandPrintsWhatTheReadmeShows) {
  TempDir dir;
  fs::current_path(dir.path());  // the tour's runs/ folders go here
  for (const auto& step : tour()) {
    std::vector<std::string> args;
    std::istringstream words(step.command.substr(std::string("build/motus ").size()));
    for (std::string w; words >> w;) {
      ASSERT_EQ(w.find_first_of("\"'$`|;&<>*"), std::string::npos) << "a tour command is plain words: " << step.command;
      args.push_back(w);
    }
    const auto r = run_motus(dir, args);
    ASSERT_EQ(r.status, 0) << step.command << "\n" << r.err;
    for (const auto& shown : step.shown)
      EXPECT_TRUE(printed(r.out, shown)) << step.command << " no longer prints\n  " << shown << "\nit printed:\n" << r.out;
  }
}

}  // namespace
