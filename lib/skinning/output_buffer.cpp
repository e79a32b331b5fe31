#include "skinning/output_buffer.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace crowdprof {
namespace {

constexpr size_t kHugePage = size_t{2} << 20;

std::align_val_t alignment(size_t bytes) {
  return std::align_val_t{bytes >= kHugePage ? kHugePage : 64};
}

}  // namespace

void* allocate_output(size_t bytes) {
  void* p = ::operator new(bytes, alignment(bytes));
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Before the first touch, so that the pages come huge; a kernel that says no
  // leaves ordinary pages, which work the same, only slower.
  if (bytes >= kHugePage) madvise(p, (bytes + kHugePage - 1) / kHugePage * kHugePage, MADV_HUGEPAGE);
#endif
  return p;
}

void free_output(void* p, size_t bytes) {
  ::operator delete(p, alignment(bytes));
}

}  // namespace crowdprof
