#pragma once
// Forrester's World2 (World Dynamics, 1971), the smallest of the Limits to Growth
// models: five stocks driven by rates that are products of table functions.
// Equations, constants and tables as docs/course.md (section 8) restates them; the standard
// run they give is tests/reference/world2.md.
// State: P (people), NR (resource units), CI (capital units), POL (pollution units),
// CIAF (fraction); time in years (the standard run goes from 1900 to 2100).
#include <map>
#include <string>

#include "motus/systems/first_order_system.hpp"
#include "motus/systems/system_catalog.hpp"

namespace motus {

// Constants and the normal rates. The normal rates may change from `switch_year` on
// (the book's policy scenarios), to the values with the suffix 1 (BRN1, ...).
struct World2Parameters {
  double LA = 135e6, PDN = 26.5, CIAFN = 0.3, ECIRN = 1, CIAFT = 15, POLS = 3.6e9, FN = 1, QLS = 1, NRI = 900e9;
  double BRN = 0.04, DRN = 0.028, CIDN = 0.025, CIGN = 0.05, FC = 1, NRUN = 1, POLN = 1;
  double switch_year = 1970;
  double BRN1 = 0.04, DRN1 = 0.028, CIDN1 = 0.025, CIGN1 = 0.05, FC1 = 1, NRUN1 = 1, POLN1 = 1;
};

class World2 final : public FirstOrderSystem {
public:
  explicit World2(const World2Parameters& parameters = {}) : p_(parameters) {}

  int size() const override { return 5; }
  std::vector<std::string> variable_names() const override { return {"P", "NR", "CI", "POL", "CIAF"}; }
  void derivative(double t, ConstVectorRef y, VectorRef dydt) override;

  // QL (quality of life) and the auxiliaries behind it.
  std::vector<std::string> auxiliary_names() const override { return {"QL", "CR", "MSL", "FR", "POLR"}; }
  void auxiliaries(double t, ConstVectorRef y, VectorRef out) const override;

private:
  World2Parameters p_;
};

SystemInfo world2_system_info();

}  // namespace motus
