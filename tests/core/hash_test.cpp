#include "lantern/core/hash.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <set>
#include <string>

using lantern::Hasher;

TEST(Hasher, DeterministicAndOrderSensitive) {
    auto h1 = Hasher().add(1).add(2.5f).add_string("light").value();
    auto h2 = Hasher().add(1).add(2.5f).add_string("light").value();
    auto h3 = Hasher().add(2.5f).add(1).add_string("light").value();
    EXPECT_EQ(h1, h2);
    EXPECT_NE(h1, h3);
}

TEST(Hasher, DistinguishesNearbyInputs) {
    std::set<std::uint64_t> seen;
    for (int i = 0; i < 10000; ++i) seen.insert(Hasher().add(i).value());
    EXPECT_EQ(seen.size(), 10000u);
    // Strings that differ only in length must differ (length is hashed).
    EXPECT_NE(Hasher().add_string("ab").value(), Hasher().add_string(std::string("ab\0", 3)).value());
}

TEST(Hasher, FloatBitPatterns) {
    EXPECT_NE(Hasher().add(0.0f).value(), Hasher().add(-0.0f).value());
    EXPECT_EQ(Hasher().add(1.0f).value(), Hasher().add(1.0f).value());
}

TEST(Hasher, KnownValueIsStableAcrossBuilds) {
    // Cache keys are written to disk by later tools: the hash must not drift silently.
    EXPECT_EQ(Hasher(0).add_u64(0).value(), lantern::mix64(lantern::mix64(0 ^ 0x9e3779b97f4a7c15ull)));
}

// Structs with padding cannot be hashed as bytes (a static_assert in Hasher::add); the trait
// says which can.
namespace {
struct Padded {
    std::uint8_t a;
    std::uint32_t b;
};
struct Packed {
    std::uint32_t a, b;
};
struct Floats {
    float x, y;
};
} // namespace
static_assert(!lantern::hash_as_bytes<Padded>, "padding bytes would enter the hash");
static_assert(lantern::hash_as_bytes<Packed>);
static_assert(!lantern::hash_as_bytes<Floats>, "float aggregates opt in explicitly");
static_assert(lantern::hash_as_bytes<float> && lantern::hash_as_bytes<std::uint16_t>);

TEST(Hash, PaddedStructsAreHashedFieldByField) {
    // Two equal values whose padding bytes differ give the same key when hashed by field.
    Padded a{}, b{};
    std::memset(&a, 0x00, sizeof a);
    std::memset(&b, 0xff, sizeof b);
    a.a = b.a = 7;
    a.b = b.b = 9;
    EXPECT_EQ(lantern::Hasher().add(a.a).add(a.b).value(), lantern::Hasher().add(b.a).add(b.b).value());
}
