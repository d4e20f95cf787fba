// 64-bit hashing for cache keys and content addressing.
//
// Hasher is a streaming FNV-1a-style mixer with a strong finaliser (splitmix64). It is
// deterministic across runs and machines of the same endianness, which cache keys need;
// it is not a cryptographic hash. Floats are hashed by bit pattern, so -0.0 and 0.0 differ
// and every NaN payload is distinct: canonicalise first where that matters.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string_view>
#include <type_traits>

namespace lantern {

constexpr std::uint64_t mix64(std::uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    x ^= x >> 31;
    return x;
}

// Types Hasher hashes as their bytes (add, add_span): those with unique object
// representations (no padding bits, no floats) and arithmetic types. A struct with padding
// would hash whatever its padding bytes hold, so keys of equal values could differ: hash
// such a struct field by field. A float aggregate whose author has checked it has no
// padding (a static_assert of its size beside it) may opt in:
//   template <> inline constexpr bool lantern::hash_as_bytes<MyType> = true;
template <typename T>
inline constexpr bool hash_as_bytes = std::has_unique_object_representations_v<T> || std::is_arithmetic_v<T>;

class Hasher {
  public:
    constexpr explicit Hasher(std::uint64_t seed = 0x6c616e7465726e00ull) : state_(seed) {}

    constexpr Hasher& add_u64(std::uint64_t v) {
        state_ = mix64(state_ ^ (v + 0x9e3779b97f4a7c15ull + (state_ << 6) + (state_ >> 2)));
        return *this;
    }
    Hasher& add_bytes(const void* data, std::size_t size) {
        const auto* p = static_cast<const unsigned char*>(data);
        while (size >= 8) {
            std::uint64_t v;
            std::memcpy(&v, p, 8);
            add_u64(v);
            p += 8;
            size -= 8;
        }
        std::uint64_t tail = size;
        for (std::size_t i = 0; i < size; ++i) tail |= std::uint64_t(p[i]) << (8 * (i + 1));
        return add_u64(tail);
    }
    template <typename T>
        requires std::is_trivially_copyable_v<T>
    Hasher& add(const T& value) {
        if constexpr (std::is_integral_v<T> || std::is_enum_v<T>) {
            return add_u64(static_cast<std::uint64_t>(value));
        } else if constexpr (std::is_same_v<T, float>) {
            return add_u64(std::bit_cast<std::uint32_t>(value));
        } else if constexpr (std::is_same_v<T, double>) {
            return add_u64(std::bit_cast<std::uint64_t>(value));
        } else {
            static_assert(hash_as_bytes<T>, "Hasher::add: T may have padding; hash it field by field, or opt in with "
                                            "lantern::hash_as_bytes (core/hash.hpp)");
            return add_bytes(&value, sizeof(T));
        }
    }
    template <typename T>
    Hasher& add_span(std::span<const T> values) {
        static_assert(hash_as_bytes<T>, "Hasher::add_span: T may have padding; hash it field by field, or opt in with "
                                        "lantern::hash_as_bytes (core/hash.hpp)");
        add_u64(values.size());
        return add_bytes(values.data(), values.size_bytes());
    }
    Hasher& add_string(std::string_view s) {
        add_u64(s.size());
        return add_bytes(s.data(), s.size());
    }
    constexpr std::uint64_t value() const { return mix64(state_); }

  private:
    std::uint64_t state_;
};

constexpr std::uint64_t hash_combine(std::uint64_t a, std::uint64_t b) {
    return Hasher(a).add_u64(b).value();
}

} // namespace lantern
