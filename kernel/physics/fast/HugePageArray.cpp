#include "physics/fast/HugePageArray.h"

#include <cstdlib>
#include <cstring>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace netsculpt {

namespace {
constexpr std::size_t kHugePage = std::size_t(2) << 20;
} // namespace

void HugePageArray::Free::operator()(double* p) const { std::free(p); }

void HugePageArray::assign(std::size_t n) {
    allocate(n);
    if (n > 0)
        std::memset(data_.get(), 0, n * sizeof(double));
}

void HugePageArray::allocate(std::size_t n) {
    if (n <= capacity_) {
        size_ = n;
        return;
    }
    data_.reset();
    size_ = capacity_ = 0;
    const std::size_t wanted = n + n / 8;
    const std::size_t bytes = (wanted * sizeof(double) + kHugePage - 1) / kHugePage * kHugePage;
    void* memory = std::aligned_alloc(kHugePage, bytes);
    if (!memory)
        throw std::bad_alloc();
#if defined(__linux__)
    madvise(memory, bytes, MADV_HUGEPAGE); // advice only: ordinary pages when refused
#endif
    data_.reset(static_cast<double*>(memory));
    size_ = n;
    capacity_ = bytes / sizeof(double);
}

} // namespace netsculpt
