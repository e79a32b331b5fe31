// Memory for skinning: the plan's batches, and every copy's skinned vertices
// and palettes, rewritten each frame.
#pragma once

#include <cstddef>
#include <new>

namespace crowdprof {

// Allocates on 64-byte boundaries: a plan batch's rows never straddle a cache
// line and aligned vector loads are allowed; a copy's output can start on a
// cache line and be streamed (output_stores.h). An allocation of 2 MiB or more
// starts on a 2 MiB boundary and asks Linux for transparent huge pages
// (madvise; Debian's default THP setting is "madvise"). At 10,000 copies a
// frame writes 1.2 GB: with 4 KiB pages that is 290,000 pages, most of them a
// TLB miss, and in a virtual machine each miss walks two page tables.
void* allocate_output(size_t bytes);
void free_output(void* p, size_t bytes);

template <typename T>
struct CacheLineAllocator {
  using value_type = T;
  CacheLineAllocator() = default;
  template <typename U>
  CacheLineAllocator(const CacheLineAllocator<U>&) {}
  T* allocate(size_t n) { return static_cast<T*>(allocate_output(n * sizeof(T))); }
  void deallocate(T* p, size_t n) { free_output(p, n * sizeof(T)); }
  template <typename U>
  bool operator==(const CacheLineAllocator<U>&) const {
    return true;
  }
};

}  // namespace crowdprof
