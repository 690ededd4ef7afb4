#include "motus/systems/world2.hpp"

#include "motus/systems/table_function.hpp"

namespace motus {
namespace {

// The table functions of World2, as docs/course.md (section 8) lists them (x points, then y points).
const TableFunction BRMM({0, 1, 2, 3, 4, 5}, {1.2, 1.0, 0.85, 0.75, 0.7, 0.7});
const TableFunction NREM({0, 0.25, 0.5, 0.75, 1}, {0, 0.15, 0.5, 0.85, 1});
const TableFunction DRMM({0, 0.5, 1, 1.5, 2, 2.5, 3, 3.5, 4, 4.5, 5}, {3, 1.8, 1, 0.8, 0.7, 0.6, 0.53, 0.5, 0.5, 0.5, 0.5});
const TableFunction DRPM({0, 10, 20, 30, 40, 50, 60}, {0.92, 1.3, 2.0, 3.2, 4.8, 6.8, 9.2});
const TableFunction DRFM({0, 0.25, 0.5, 0.75, 1, 1.25, 1.5, 1.75, 2}, {30, 3, 2, 1.4, 1, 0.7, 0.6, 0.5, 0.5});
const TableFunction DRCM({0, 1, 2, 3, 4, 5}, {0.9, 1.0, 1.2, 1.5, 1.9, 3.0});
const TableFunction BRCM({0, 1, 2, 3, 4, 5}, {1.05, 1.0, 0.9, 0.7, 0.6, 0.55});
const TableFunction BRFM({0, 1, 2, 3, 4}, {0, 1, 1.6, 1.9, 2.0});
const TableFunction BRPM({0, 10, 20, 30, 40, 50, 60}, {1.02, 0.9, 0.7, 0.4, 0.25, 0.15, 0.1});
const TableFunction FCM({0, 1, 2, 3, 4, 5}, {2.4, 1.0, 0.6, 0.4, 0.3, 0.2});
const TableFunction FPCI({0, 1, 2, 3, 4, 5, 6}, {0.5, 1.0, 1.4, 1.7, 1.9, 2.05, 2.2});
const TableFunction CIM({0, 1, 2, 3, 4, 5}, {0.1, 1.0, 1.8, 2.4, 2.8, 3.0});
const TableFunction FPM({0, 10, 20, 30, 40, 50, 60}, {1.02, 0.9, 0.65, 0.35, 0.2, 0.1, 0.05});
const TableFunction POLCM({0, 1, 2, 3, 4, 5}, {0.05, 1, 3, 5.4, 7.4, 8});
const TableFunction POLAT({0, 10, 20, 30, 40, 50, 60}, {0.6, 2.5, 5, 8, 11.5, 15.5, 20});
const TableFunction CFIFR({0, 0.5, 1, 1.5, 2}, {1, 0.6, 0.3, 0.15, 0.1});
const TableFunction QLM({0, 1, 2, 3, 4, 5}, {0.2, 1, 1.7, 2.3, 2.7, 2.9});
const TableFunction QLC({0, 0.5, 1, 1.5, 2, 2.5, 3, 3.5, 4, 4.5, 5}, {2, 1.3, 1, 0.75, 0.55, 0.45, 0.38, 0.3, 0.25, 0.22, 0.2});
const TableFunction QLF({0, 1, 2, 3, 4}, {0, 1, 1.8, 2.4, 2.7});
const TableFunction QLP({0, 10, 20, 30, 40, 50, 60}, {1.04, 0.85, 0.6, 0.3, 0.15, 0.05, 0.02});
const TableFunction NRMM({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, {0, 1, 1.8, 2.4, 2.9, 3.3, 3.6, 3.8, 3.9, 3.95, 4});
const TableFunction CIQR({0, 0.5, 1, 1.5, 2}, {0.7, 0.8, 1, 1.5, 2});

// The auxiliaries, computed from the state as the reference lists them.
struct Auxiliaries {
  double CR, CIR, POLR, NRFR, CIRA, FR, ECIR, MSL;
};

Auxiliaries auxiliaries_of(const World2Parameters& p, double FC, ConstVectorRef y) {
  const double P = y[0], NR = y[1], CI = y[2], POL = y[3], CIAF = y[4];
  Auxiliaries a{};
  a.CR = P / (p.LA * p.PDN);
  a.CIR = CI / P;
  a.POLR = POL / p.POLS;
  a.NRFR = NR / p.NRI;
  a.CIRA = a.CIR * CIAF / p.CIAFN;
  a.FR = FCM(a.CR) * FPCI(a.CIRA) * FPM(a.POLR) * FC / p.FN;
  a.ECIR = a.CIR * (1 - CIAF) * NREM(a.NRFR) / (1 - p.CIAFN);
  a.MSL = a.ECIR / p.ECIRN;
  return a;
}

}  // namespace

void World2::derivative(double t, ConstVectorRef y, VectorRef dydt) {
  ++evaluations;
  const bool switched = t >= p_.switch_year;
  const double BRN = switched ? p_.BRN1 : p_.BRN, DRN = switched ? p_.DRN1 : p_.DRN;
  const double CIDN = switched ? p_.CIDN1 : p_.CIDN, CIGN = switched ? p_.CIGN1 : p_.CIGN;
  const double FC = switched ? p_.FC1 : p_.FC, NRUN = switched ? p_.NRUN1 : p_.NRUN;
  const double POLN = switched ? p_.POLN1 : p_.POLN;

  const double P = y[0], CI = y[2], POL = y[3], CIAF = y[4];
  const Auxiliaries a = auxiliaries_of(p_, FC, y);

  const double BR = P * BRN * BRMM(a.MSL) * BRCM(a.CR) * BRFM(a.FR) * BRPM(a.POLR);
  const double DR = P * DRN * DRMM(a.MSL) * DRPM(a.POLR) * DRFM(a.FR) * DRCM(a.CR);
  dydt[0] = BR - DR;                                                  // P'
  dydt[1] = -P * NRUN * NRMM(a.MSL);                                  // NR'
  dydt[2] = P * CIM(a.MSL) * CIGN - CI * CIDN;                        // CI'
  dydt[3] = P * POLN * POLCM(a.CIR) - POL / POLAT(a.POLR);            // POL'
  dydt[4] = (CFIFR(a.FR) * CIQR(QLM(a.MSL) / QLF(a.FR)) - CIAF) / p_.CIAFT;  // CIAF'
}

void World2::auxiliaries(double t, ConstVectorRef y, VectorRef out) const {
  const double FC = t >= p_.switch_year ? p_.FC1 : p_.FC;
  const Auxiliaries a = auxiliaries_of(p_, FC, y);
  const double QL = p_.QLS * QLM(a.MSL) * QLC(a.CR) * QLF(a.FR) * QLP(a.POLR);
  out[0] = QL;
  out[1] = a.CR;
  out[2] = a.MSL;
  out[3] = a.FR;
  out[4] = a.POLR;
}

// Every field of World2Parameters, settable from a scene by the same name.
struct World2Field {
  const char* name;
  double World2Parameters::*field;
  const char* meaning;
};
static const World2Field kWorld2Fields[] = {
    {"LA", &World2Parameters::LA, "land area, km^2"},
    {"PDN", &World2Parameters::PDN, "normal population density, people/km^2"},
    {"CIAFN", &World2Parameters::CIAFN, "normal capital-investment-in-agriculture fraction"},
    {"ECIRN", &World2Parameters::ECIRN, "normal effective capital-investment ratio"},
    {"CIAFT", &World2Parameters::CIAFT, "CIAF adjustment time, years"},
    {"POLS", &World2Parameters::POLS, "pollution standard, pollution units"},
    {"FN", &World2Parameters::FN, "food normal"},
    {"QLS", &World2Parameters::QLS, "quality-of-life standard"},
    {"NRI", &World2Parameters::NRI, "initial natural resources, resource units"},
    {"BRN", &World2Parameters::BRN, "birth rate normal, 1/year"},
    {"DRN", &World2Parameters::DRN, "death rate normal, 1/year"},
    {"CIDN", &World2Parameters::CIDN, "capital-investment discard normal, 1/year"},
    {"CIGN", &World2Parameters::CIGN, "capital-investment generation normal, capital units/person/year"},
    {"FC", &World2Parameters::FC, "food coefficient"},
    {"NRUN", &World2Parameters::NRUN, "natural-resource usage normal, resource units/person/year"},
    {"POLN", &World2Parameters::POLN, "pollution normal, pollution units/person/year"},
    {"switch_year", &World2Parameters::switch_year, "year from which the policy values (BRN1, ...) apply"},
    {"BRN1", &World2Parameters::BRN1, "BRN from switch_year on"},
    {"DRN1", &World2Parameters::DRN1, "DRN from switch_year on"},
    {"CIDN1", &World2Parameters::CIDN1, "CIDN from switch_year on"},
    {"CIGN1", &World2Parameters::CIGN1, "CIGN from switch_year on"},
    {"FC1", &World2Parameters::FC1, "FC from switch_year on"},
    {"NRUN1", &World2Parameters::NRUN1, "NRUN from switch_year on"},
    {"POLN1", &World2Parameters::POLN1, "POLN from switch_year on"},
};

SystemInfo world2_system_info() {
  const World2Parameters defaults;
  std::vector<ParameterInfo> parameters;
  for (const auto& f : kWorld2Fields) parameters.push_back({f.name, defaults.*f.field, f.meaning});
  auto make = [](const std::map<std::string, double>& values) -> std::unique_ptr<FirstOrderSystem> {
    World2Parameters p;
    for (const auto& f : kWorld2Fields)
      if (auto it = values.find(f.name); it != values.end()) p.*f.field = it->second;
    return std::make_unique<World2>(p);
  };
  return {"world2",
          "Forrester's World2, the Limits to Growth model family",
          {"P", "NR", "CI", "POL", "CIAF"},
          std::move(parameters),
          make,
          {"population (people)", "natural resources (resource units)", "capital investment (capital units)",
           "pollution (pollution units)", "capital in agriculture (fraction)"},
          "year"};
}

}  // namespace motus
