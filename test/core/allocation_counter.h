// Counts every heap allocation of a test binary, for the "no heap allocation" assertions of
// contact_solver_contract_test.cpp, contact_solver_mapped_drilling_test.cpp and step_test.cpp:
// nonsmooth_sim::test::HeapAllocations() is the
// number of allocations made so far by any thread (frees are not counted); a test takes the
// difference around the code under test.
//
// Include it from exactly ONE translation unit of an executable (every test/core/*_test.cpp is
// one): it defines process-wide functions.
//
// Counted at the malloc level, not at operator new: Eigen's dynamic matrices and vectors allocate
// with std::malloc directly (Eigen/src/Core/util/Memory.h, aligned_malloc), so a counter in a
// replaced operator new would not see a VectorXd or MatrixXd (re)sized by the solver or the step,
// the allocations these tests are about. operator new (libstdc++'s and the sanitizers') allocates
// through malloc or the sanitizer's allocator, so containers are counted either way. Two ways:
//
//  - plain builds: the malloc family is replaced (glibc manual, "Replacing malloc") and forwards
//    to glibc's own __libc_* implementation;
//  - sanitized builds (ASan, TSan; cmake/sanitizers.cmake): the sanitizer runtime owns malloc (a
//    program that replaces it crashes AddressSanitizer at start-up) and reports every allocation
//    of its allocator (malloc, calloc, realloc, aligned, operator new) to hooks installed with
//    __sanitizer_install_malloc_and_free_hooks; the counter is one of them. No replacement, so
//    ASan keeps checking new/delete and malloc/free mismatches in these binaries too.
#ifndef NONSMOOTH_SIM_TEST_CORE_ALLOCATION_COUNTER_H_
#define NONSMOOTH_SIM_TEST_CORE_ALLOCATION_COUNTER_H_

#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstdlib>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define NONSMOOTH_SIM_TEST_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || \
    __has_feature(memory_sanitizer)
#define NONSMOOTH_SIM_TEST_SANITIZED 1
#endif
#endif

namespace nonsmooth_sim {
namespace test {
namespace allocation_counter_detail {
inline std::atomic<long> heap_allocations{0};
}  // namespace allocation_counter_detail

// Heap allocations made so far by this process (any thread, any allocation function).
inline long HeapAllocations() {
  return allocation_counter_detail::heap_allocations.load(std::memory_order_relaxed);
}
}  // namespace test
}  // namespace nonsmooth_sim

#ifdef NONSMOOTH_SIM_TEST_SANITIZED

// sanitizer_common's allocator interface (not among GCC 12's installed sanitizer headers).
extern "C" int __sanitizer_install_malloc_and_free_hooks(
    void (*malloc_hook)(const volatile void* pointer, std::size_t size),
    void (*free_hook)(const volatile void* pointer));

namespace nonsmooth_sim {
namespace test {
namespace allocation_counter_detail {
inline void CountAllocation(const volatile void*, std::size_t) {
  heap_allocations.fetch_add(1, std::memory_order_relaxed);
}
inline void IgnoreFree(const volatile void*) {}
// installed during static initialisation, before any test runs (both hooks are required)
inline const int hooks_installed =
    __sanitizer_install_malloc_and_free_hooks(&CountAllocation, &IgnoreFree);
}  // namespace allocation_counter_detail
}  // namespace test
}  // namespace nonsmooth_sim

#else  // plain build: replace the malloc family (glibc), forward to glibc's implementation

extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);
void* __libc_valloc(std::size_t size);
void* __libc_pvalloc(std::size_t size);
void __libc_free(void* pointer);

void* malloc(std::size_t size) noexcept {
  nonsmooth_sim::test::allocation_counter_detail::heap_allocations.fetch_add(1);
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) noexcept {
  nonsmooth_sim::test::allocation_counter_detail::heap_allocations.fetch_add(1);
  return __libc_calloc(count, size);
}
void* realloc(void* pointer, std::size_t size) noexcept {
  nonsmooth_sim::test::allocation_counter_detail::heap_allocations.fetch_add(1);
  return __libc_realloc(pointer, size);
}
void* reallocarray(void* pointer, std::size_t count, std::size_t size) noexcept {
  nonsmooth_sim::test::allocation_counter_detail::heap_allocations.fetch_add(1);
  std::size_t bytes = 0;
  if (__builtin_mul_overflow(count, size, &bytes)) {
    errno = ENOMEM;
    return nullptr;
  }
  return __libc_realloc(pointer, bytes);
}
void* memalign(std::size_t alignment, std::size_t size) noexcept {
  nonsmooth_sim::test::allocation_counter_detail::heap_allocations.fetch_add(1);
  return __libc_memalign(alignment, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) noexcept {
  nonsmooth_sim::test::allocation_counter_detail::heap_allocations.fetch_add(1);
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** pointer, std::size_t alignment, std::size_t size) noexcept {
  nonsmooth_sim::test::allocation_counter_detail::heap_allocations.fetch_add(1);
  if (alignment % sizeof(void*) != 0 || (alignment & (alignment - 1)) != 0) return EINVAL;
  void* result = __libc_memalign(alignment, size);
  if (result == nullptr) return ENOMEM;
  *pointer = result;
  return 0;
}
void* valloc(std::size_t size) noexcept {
  nonsmooth_sim::test::allocation_counter_detail::heap_allocations.fetch_add(1);
  return __libc_valloc(size);
}
void* pvalloc(std::size_t size) noexcept {
  nonsmooth_sim::test::allocation_counter_detail::heap_allocations.fetch_add(1);
  return __libc_pvalloc(size);
}
void free(void* pointer) noexcept { __libc_free(pointer); }
}  // extern "C"

#endif  // NONSMOOTH_SIM_TEST_SANITIZED

#endif  // NONSMOOTH_SIM_TEST_CORE_ALLOCATION_COUNTER_H_
