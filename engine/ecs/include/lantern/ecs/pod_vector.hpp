// A vector of trivially copyable values that grows with realloc.
//
// Component pools hold millions of small values in arrays that grow one element at a
// time. std::vector grows by allocating a new block and copying into it, so an array of
// n bytes has touched about 2n bytes of fresh memory (each one a page fault) by the time it
// holds n. realloc grows a large block in place or moves its pages (mremap) without
// copying them, so each byte is faulted in once. Creating 1M entities with two components
// spent 62 % of its time in the kernel's page faults with std::vector (benchmarks/peers,
// docs/ecs.md). Values must be trivially copyable and no more aligned than malloc
// guarantees; Pool falls back to std::vector for other component types.
//
// Blocks of `detail::pod_map_bytes` (1 MiB) and more are mapped from the kernel directly on Linux and grown with
// mremap. realloc would do the same only while glibc keeps such blocks mapped: after a few
// large frees it raises its mmap threshold (up to 32 MiB) and serves them from the heap,
// where growing copies (the 1M-entity create spent 8 % of its time in memmove). Mapped
// blocks also ask for transparent huge pages, so a large array faults in 2 MiB at a time.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <new>
#include <type_traits>
#include <utility>

namespace lantern::ecs {

namespace detail {
// Page-granular blocks for PodVector (src/pod_vector.cpp). pod_map and pod_remap return
// null where the platform has no such mapping or the kernel refuses; PodVector then uses
// malloc. A mapped block's size is rounded up to whole pages.
inline constexpr std::size_t pod_map_bytes = std::size_t(1) << 20;
void* pod_map(std::size_t bytes);
void* pod_remap(void* block, std::size_t old_bytes, std::size_t new_bytes);
void pod_unmap(void* block, std::size_t bytes);
} // namespace detail

template <typename T>
inline constexpr bool pod_vector_compatible =
    std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T> && alignof(T) <= alignof(std::max_align_t);

template <typename T>
class PodVector {
    static_assert(pod_vector_compatible<T>, "PodVector holds trivially copyable, malloc-aligned values only");

  public:
    using value_type = T;

    PodVector() = default;
    ~PodVector() { release(); }
    PodVector(const PodVector&) = delete;
    PodVector& operator=(const PodVector&) = delete;
    PodVector(PodVector&& other) noexcept
        : data_(std::exchange(other.data_, nullptr)), size_(std::exchange(other.size_, 0)),
          capacity_(std::exchange(other.capacity_, 0)), mapped_(std::exchange(other.mapped_, false)) {}
    PodVector& operator=(PodVector&& other) noexcept {
        if (this != &other) {
            release();
            data_ = std::exchange(other.data_, nullptr);
            size_ = std::exchange(other.size_, 0);
            capacity_ = std::exchange(other.capacity_, 0);
            mapped_ = std::exchange(other.mapped_, false);
        }
        return *this;
    }

    std::size_t size() const { return size_; }
    std::size_t capacity() const { return capacity_; }
    bool empty() const { return size_ == 0; }
    bool mapped() const { return mapped_; } // the block came from the kernel (see above)
    T* data() { return data_; }
    const T* data() const { return data_; }
    T* begin() { return data_; }
    T* end() { return data_ + size_; }
    const T* begin() const { return data_; }
    const T* end() const { return data_ + size_; }
    T& operator[](std::size_t i) { return data_[i]; }
    const T& operator[](std::size_t i) const { return data_[i]; }
    T& back() { return data_[size_ - 1]; }
    const T& back() const { return data_[size_ - 1]; }

    // The value is copied before the array may move: it may be one of the elements.
    void push_back(const T& value) {
        if (size_ == capacity_) {
            const T copy = value;
            grow(size_ + 1);
            std::memcpy(static_cast<void*>(data_ + size_), &copy, sizeof(T));
        } else {
            std::memcpy(static_cast<void*>(data_ + size_), &value, sizeof(T));
        }
        ++size_;
    }
    template <typename... Args>
    T& emplace_back(Args&&... args) {
        if (size_ == capacity_) {
            push_back(make(std::forward<Args>(args)...));
            return back();
        }
        T* slot = ::new (static_cast<void*>(data_ + size_)) T(make(std::forward<Args>(args)...));
        ++size_;
        return *slot;
    }
    void pop_back() { --size_; }
    void clear() { size_ = 0; }
    void reserve(std::size_t n) {
        if (n > capacity_) reallocate(n);
    }
    // Grows with value-initialised elements, or shrinks.
    void resize(std::size_t n) {
        if (n > capacity_) grow(n);
        for (std::size_t i = size_; i < n; ++i) ::new (static_cast<void*>(data_ + i)) T();
        size_ = n;
    }

  private:
    // Aggregates by braces (parenthesised aggregate initialisation is not in every compiler
    // Lantern builds with), other types by their constructors.
    template <typename... Args>
    static T make(Args&&... args) {
        if constexpr (std::is_aggregate_v<T>)
            return T{std::forward<Args>(args)...};
        else
            return T(std::forward<Args>(args)...);
    }

    void grow(std::size_t at_least) {
        std::size_t n = capacity_ < 16 ? 16 : capacity_ * 2;
        reallocate(n < at_least ? at_least : n);
    }
    void reallocate(std::size_t n) {
        if (n > std::size_t(-1) / sizeof(T)) throw std::bad_alloc();
        const std::size_t bytes = n * sizeof(T);
        void* p = nullptr;
        bool mapped = false;
        if (bytes >= detail::pod_map_bytes) {
            if (mapped_) {
                p = detail::pod_remap(data_, capacity_ * sizeof(T), bytes);
            } else if ((p = detail::pod_map(bytes)) != nullptr) {
                if (size_) std::memcpy(p, static_cast<const void*>(data_), size_ * sizeof(T));
                std::free(data_);
            }
            mapped = p != nullptr;
        }
        if (!p) {
            if (mapped_) { // a mapped block the kernel would not grow: copy it into the heap
                p = std::malloc(bytes);
                if (p && size_) std::memcpy(p, static_cast<const void*>(data_), size_ * sizeof(T));
                if (p) detail::pod_unmap(data_, capacity_ * sizeof(T));
            } else {
                p = std::realloc(static_cast<void*>(data_), bytes);
            }
        }
        if (!p) throw std::bad_alloc();
        data_ = static_cast<T*>(p);
        capacity_ = n;
        mapped_ = mapped;
    }
    void release() {
        if (mapped_)
            detail::pod_unmap(data_, capacity_ * sizeof(T));
        else
            std::free(data_);
    }

    T* data_ = nullptr;
    std::size_t size_ = 0;
    std::size_t capacity_ = 0;
    bool mapped_ = false; // data_ came from detail::pod_map
};

} // namespace lantern::ecs
