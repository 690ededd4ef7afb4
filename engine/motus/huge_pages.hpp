#pragma once
// Big arrays on huge pages. At 10^6 balls the collisions' arrays are tens of MB, read in the grid's
// order rather than the array's: with 4 kB pages nearly every read of another ball's data needs a
// page-table walk (the core's TLB covers a few MB), with 2 MB pages few do. Linux backs memory with
// huge pages where a program asks for them (transparent huge pages in "madvise" mode, Debian's
// default); elsewhere the advice is a no-op and the arrays are ordinary memory.
#include <cstddef>
#include <memory>
#include <new>
#include <vector>

namespace motus {

inline constexpr std::size_t kHugePage = std::size_t{2} << 20;

// Asks the kernel to back the whole 2 MB pages of [p, p + bytes) with huge pages, from their first
// touch on. (Memory already touched keeps its small pages.)
void advise_huge_pages(void* p, std::size_t bytes);

// Fresh memory for `bytes` (a multiple of kHugePage), starting on a huge page's boundary and advised;
// nullptr when there is none. Given back with release_huge_pages(p, bytes). (Straight from the
// kernel, not from malloc: memory malloc hands out again has been touched, and keeps small pages.)
void* map_huge_pages(std::size_t bytes);
void release_huge_pages(void* p, std::size_t bytes);

// std::allocator for small arrays; an array of at least one huge page gets whole huge pages of its own.
template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kHugePage) return std::allocator<T>().allocate(n);
    void* p = map_huge_pages(whole_pages(bytes));
    if (!p) throw std::bad_alloc();
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t n) noexcept {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kHugePage) {
      std::allocator<T>().deallocate(p, n);
    } else {
      release_huge_pages(p, whole_pages(bytes));
    }
  }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }

private:
  static std::size_t whole_pages(std::size_t bytes) { return (bytes + kHugePage - 1) / kHugePage * kHugePage; }
};

// A std::vector whose storage, once big, is on huge pages.
template <class T>
using BigArray = std::vector<T, HugePageAllocator<T>>;

}  // namespace motus
