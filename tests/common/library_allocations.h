// Counts, or fails on purpose, the heap allocations one shared library makes itself: operator new
// called from code in that library's executable segment (inlined standard-library templates
// included). Linking library_allocations.cpp into a test replaces every form of operator new and
// delete of the program; allocations of the driver, the validation layer or the test are neither
// counted nor failed.
#pragma once

namespace sao::test {

// Locates the library that holds `symbol` (e.g. the address of one of its exported functions).
// False when it cannot be found.
bool watchLibraryOf(const void* symbol);

// Counting runs between start and stop; count() is the number since the last start.
void startCountingAllocations();
void stopCountingAllocations();
long countedAllocations();

// Armed with n > 0, the library's nth allocation from now throws std::bad_alloc (0 disarms);
// allocationFailed() says whether it happened since arming.
void failLibraryAllocation(long n);
bool allocationFailed();

}  // namespace sao::test
