// Replacements of every global operator new and delete, counting the calls. They must be
// linked whole (cortex_m3_add_firmware links the platform with WHOLE_ARCHIVE): an archive
// member pulled in only on demand can lose to libstdc++'s own operator new.
#include <malloc.h>

#include <cstdio>
#include <cstdlib>
#include <new>

#include "testbench/cortex_m3/platform.hpp"

namespace intgrid::cortex_m3 {
namespace {

// Single core, and no allocation from interrupt handlers: plain counters suffice.
std::size_t allocation_count = 0;
std::size_t deallocation_count = 0;

void* allocate(std::size_t size) {
  ++allocation_count;
  return std::malloc(size == 0 ? 1 : size);
}

void* allocate(std::size_t size, std::align_val_t alignment) {
  ++allocation_count;
  return memalign(static_cast<std::size_t>(alignment), size == 0 ? 1 : size);
}

// Without exceptions there is no std::bad_alloc to throw.
void* or_out_of_memory(void* pointer, std::size_t size) {
  if (pointer == nullptr) {
    std::fprintf(stderr, "operator new: out of memory (%u bytes)\n", size);
    std::abort();
  }
  return pointer;
}

void deallocate(void* pointer) {
  if (pointer == nullptr) return;
  ++deallocation_count;
  std::free(pointer);
}

}  // namespace

std::size_t allocations() {
  return allocation_count;
}
std::size_t deallocations() {
  return deallocation_count;
}

}  // namespace intgrid::cortex_m3

using intgrid::cortex_m3::allocate;
using intgrid::cortex_m3::deallocate;
using intgrid::cortex_m3::or_out_of_memory;

void* operator new(std::size_t size) {
  return or_out_of_memory(allocate(size), size);
}
void* operator new[](std::size_t size) {
  return or_out_of_memory(allocate(size), size);
}
void* operator new(std::size_t size, std::align_val_t alignment) {
  return or_out_of_memory(allocate(size, alignment), size);
}
void* operator new[](std::size_t size, std::align_val_t alignment) {
  return or_out_of_memory(allocate(size, alignment), size);
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  return allocate(size);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  return allocate(size);
}
void* operator new(std::size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return allocate(size, alignment);
}
void* operator new[](std::size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return allocate(size, alignment);
}

void operator delete(void* pointer) noexcept {
  deallocate(pointer);
}
void operator delete[](void* pointer) noexcept {
  deallocate(pointer);
}
void operator delete(void* pointer, std::size_t) noexcept {
  deallocate(pointer);
}
void operator delete[](void* pointer, std::size_t) noexcept {
  deallocate(pointer);
}
void operator delete(void* pointer, std::align_val_t) noexcept {
  deallocate(pointer);
}
void operator delete[](void* pointer, std::align_val_t) noexcept {
  deallocate(pointer);
}
void operator delete(void* pointer, std::size_t, std::align_val_t) noexcept {
  deallocate(pointer);
}
void operator delete[](void* pointer, std::size_t, std::align_val_t) noexcept {
  deallocate(pointer);
}
void operator delete(void* pointer, const std::nothrow_t&) noexcept {
  deallocate(pointer);
}
void operator delete[](void* pointer, const std::nothrow_t&) noexcept {
  deallocate(pointer);
}
void operator delete(void* pointer, std::align_val_t, const std::nothrow_t&) noexcept {
  deallocate(pointer);
}
void operator delete[](void* pointer, std::align_val_t, const std::nothrow_t&) noexcept {
  deallocate(pointer);
}
