#include "lantern/ecs/pod_vector.hpp"

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace lantern::ecs::detail {

#if defined(__linux__)
namespace {

std::size_t whole_pages(std::size_t bytes) {
    static const std::size_t page = std::size_t(sysconf(_SC_PAGESIZE));
    return (bytes + page - 1) / page * page;
}

// Transparent huge pages where the system allows them on request ("madvise" mode, Debian's
// default): a fault then fills 2 MiB instead of 4 KiB. Advice only; a refusal changes nothing.
void advise_huge(void* block, std::size_t bytes) {
#if defined(MADV_HUGEPAGE)
    ::madvise(block, bytes, MADV_HUGEPAGE);
#else
    (void)block;
    (void)bytes;
#endif
}

} // namespace

void* pod_map(std::size_t bytes) {
    const std::size_t size = whole_pages(bytes);
    void* p = ::mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) return nullptr;
    advise_huge(p, size);
    return p;
}

void* pod_remap(void* block, std::size_t old_bytes, std::size_t new_bytes) {
    const std::size_t size = whole_pages(new_bytes);
    void* p = ::mremap(block, whole_pages(old_bytes), size, MREMAP_MAYMOVE);
    if (p == MAP_FAILED) return nullptr;
    advise_huge(p, size);
    return p;
}

void pod_unmap(void* block, std::size_t bytes) {
    if (block) ::munmap(block, whole_pages(bytes));
}
#else
void* pod_map(std::size_t) { return nullptr; }
void* pod_remap(void*, std::size_t, std::size_t) { return nullptr; }
void pod_unmap(void*, std::size_t) {}
#endif

} // namespace lantern::ecs::detail
