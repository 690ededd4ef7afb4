// Big arrays on huge pages (engine/motus/huge_pages.hpp): an array of a huge page or more starts on
// a 2 MB boundary, is advised (the kernel's smaps shows the advice, "hg"), and holds its values
// through growth and copies; a small array is ordinary memory.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "motus/huge_pages.hpp"

namespace {

using motus::BigArray;
using motus::kHugePage;

// The VmFlags line of the mapping that holds `p`, from /proc/self/smaps ("" if none is found).
std::string vm_flags_at(const void* p) {
  const auto address = reinterpret_cast<std::uintptr_t>(p);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t begin = 0, end = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> begin >> dash >> end && dash == '-' && line.find(':') > line.find(' ')) {
      inside = address >= begin && address < end;
      continue;
    }
    if (inside && line.rfind("VmFlags:", 0) == 0) return line;
  }
  return "";
}

TEST(HugePages, ABigArrayStartsOnAHugePageIsAdvisedAndKeepsItsValues) {
  BigArray<double> big(3 * kHugePage / sizeof(double) + 5);  // three huge pages and a bit
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(big.data()) % kHugePage, 0u);
  for (size_t i = 0; i < big.size(); ++i) big[i] = static_cast<double>(i);
  // (With transparent huge pages built into the kernel, the mapping carries the advice.)
  if (std::filesystem::exists("/sys/kernel/mm/transparent_hugepage/enabled")) {
    EXPECT_NE(vm_flags_at(big.data()).find(" hg"), std::string::npos) << vm_flags_at(big.data());
  }
  big.resize(5 * kHugePage / sizeof(double));  // grown: moved to new pages, values kept
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(big.data()) % kHugePage, 0u);
  for (size_t i = 0; i < 3 * kHugePage / sizeof(double) + 5; ++i) ASSERT_EQ(big[i], static_cast<double>(i));
  const BigArray<double> copy = big;
  EXPECT_EQ(copy, big);
}

TEST(HugePages, ASmallArrayIsOrdinaryMemory) {
  BigArray<int> small(1000, 7);
  EXPECT_EQ(small.size(), 1000u);
  EXPECT_EQ(small[999], 7);
  const std::string flags = vm_flags_at(small.data());
  ASSERT_EQ(flags.rfind("VmFlags:", 0), 0u) << "its mapping was not found in /proc/self/smaps";  // (else "" passes)
  EXPECT_EQ(flags.find(" hg"), std::string::npos) << flags;
}

}  // namespace
