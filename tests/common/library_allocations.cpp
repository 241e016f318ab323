#include "library_allocations.h"

#include <dlfcn.h>
#include <link.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <new>

namespace {

std::uintptr_t gBegin = 0, gEnd = 0;  // the watched library's executable segment
std::atomic<bool> gCounting{false};
std::atomic<long> gCount{0};
std::atomic<long> gFailAt{0};  // 0: disarmed
std::atomic<long> gSinceArmed{0};
std::atomic<bool> gFailed{false};

// Counts an allocation of the watched library; throws when it is the one armed to fail.
void observe(void* caller) {
  const auto at = reinterpret_cast<std::uintptr_t>(caller);
  if (at < gBegin || at >= gEnd) return;
  if (gCounting.load(std::memory_order_relaxed)) gCount.fetch_add(1, std::memory_order_relaxed);
  const long failAt = gFailAt.load(std::memory_order_relaxed);
  if (failAt > 0 && gSinceArmed.fetch_add(1) + 1 == failAt) {
    gFailed = true;
    throw std::bad_alloc();
  }
}

void* allocate(std::size_t n, void* caller) {
  observe(caller);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}

void* alignedAllocate(std::size_t n, std::align_val_t a) noexcept {
  const std::size_t align = std::max(std::size_t(a), sizeof(void*));
  return std::aligned_alloc(align, (std::max<std::size_t>(n, 1) + align - 1) / align * align);
}

}  // namespace

// Every form is replaced, all on malloc/free (a form left to the runtime and freed by ours is an
// alloc-dealloc mismatch under AddressSanitizer).
void* operator new(std::size_t n) { return allocate(n, __builtin_return_address(0)); }
void* operator new[](std::size_t n) { return allocate(n, __builtin_return_address(0)); }
// The nothrow and aligned forms are not observed: the library uses neither, the validation layer
// the nothrow one.
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return std::malloc(n ? n : 1); }
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void* operator new(std::size_t n, std::align_val_t a) {
  observe(__builtin_return_address(0));
  if (void* p = alignedAllocate(n, a)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n, std::align_val_t a) { return operator new(n, a); }
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return alignedAllocate(n, a);
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t& t) noexcept { return operator new(n, a, t); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }

namespace sao::test {

bool watchLibraryOf(const void* symbol) {
  Dl_info info{};
  if (dladdr(symbol, &info) == 0) return false;
  gBegin = gEnd = 0;
  dl_iterate_phdr(
      [](dl_phdr_info* lib, std::size_t, void* base) {
        if (reinterpret_cast<void*>(lib->dlpi_addr) != base) return 0;
        for (int i = 0; i < lib->dlpi_phnum; ++i) {
          const ElfW(Phdr)& ph = lib->dlpi_phdr[i];
          if (ph.p_type == PT_LOAD && (ph.p_flags & PF_X)) {
            gBegin = lib->dlpi_addr + ph.p_vaddr;
            gEnd = gBegin + ph.p_memsz;
          }
        }
        return 1;
      },
      info.dli_fbase);
  return gBegin < gEnd;
}

void startCountingAllocations() {
  gCount = 0;
  gCounting = true;
}
void stopCountingAllocations() { gCounting = false; }
long countedAllocations() { return gCount.load(); }

void failLibraryAllocation(long n) {
  gSinceArmed = 0;
  gFailed = false;
  gFailAt = n;
}
bool allocationFailed() { return gFailed.load(); }

}  // namespace sao::test
