#include "lantern/ecs/pod_vector.hpp"
#include "lantern/ecs/pool.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

using lantern::ecs::PodVector;

namespace {
struct Pair {
    std::uint64_t a = 0, b = 0;
};
struct WithCtor {
    WithCtor(int x, int y) : sum(x + y) {}
    int sum;
};
} // namespace

TEST(PodVector, GrowsLikeAVectorThroughManyReallocations) {
    PodVector<std::uint32_t> v;
    std::vector<std::uint32_t> model;
    for (std::uint32_t i = 0; i < 300'000; ++i) {
        v.push_back(i * 2654435761u);
        model.push_back(i * 2654435761u);
        if (i % 7 == 3) {
            v.pop_back();
            model.pop_back();
        }
    }
    ASSERT_EQ(v.size(), model.size());
    EXPECT_GE(v.capacity(), v.size());
    for (std::size_t i = 0; i < model.size(); ++i) ASSERT_EQ(v[i], model[i]) << i;
    EXPECT_EQ(v.back(), model.back());
    std::size_t n = 0;
    for (std::uint32_t x : v) n += x == model[n] ? 1 : 0;
    EXPECT_EQ(n, model.size());
}

TEST(PodVector, PushingOneOfItsOwnElementsSurvivesTheReallocation) {
    PodVector<Pair> v;
    v.push_back({1, 2});
    for (int i = 0; i < 1000; ++i) {
        v.push_back(v[0]); // at every capacity boundary the source moves
        v.emplace_back(v.back());
    }
    for (const Pair& p : v) {
        ASSERT_EQ(p.a, 1u);
        ASSERT_EQ(p.b, 2u);
    }
}

TEST(PodVector, EmplacesAggregatesAndConstructedTypes) {
    PodVector<Pair> pairs;
    for (std::uint64_t i = 0; i < 100; ++i) EXPECT_EQ(pairs.emplace_back(i, i + 1).b, i + 1);
    PodVector<WithCtor> made;
    for (int i = 0; i < 100; ++i) EXPECT_EQ(made.emplace_back(i, 2 * i).sum, 3 * i);
    ASSERT_EQ(made.size(), 100u);
    EXPECT_EQ(made[99].sum, 297);
}

TEST(PodVector, ResizeValueInitialisesReserveKeepsContentsMoveTransfers) {
    PodVector<std::uint64_t> v;
    v.resize(5);
    for (std::uint64_t x : v) EXPECT_EQ(x, 0u);
    v[4] = 44;
    v.reserve(1'000'000);
    EXPECT_GE(v.capacity(), 1'000'000u);
    EXPECT_EQ(v.size(), 5u);
    EXPECT_EQ(v[4], 44u);
    v.resize(2);
    v.resize(4);
    EXPECT_EQ(v[3], 0u); // regrown elements are value-initialised again
    PodVector<std::uint64_t> w(std::move(v));
    EXPECT_TRUE(v.empty());
    EXPECT_EQ(v.data(), nullptr);
    EXPECT_EQ(w.size(), 4u);
    v = std::move(w);
    EXPECT_EQ(v.size(), 4u);
    v.clear();
    EXPECT_TRUE(v.empty());
}

TEST(PodVector, LargeBlocksAreMappedGrownInPlaceAndKeepTheirContents) {
    // Across pod_map_bytes the block moves from the heap to a mapping (one copy), then grows
    // by mremap; moves hand the mapping over, and assigning over a mapped vector unmaps it.
    constexpr std::size_t large = 3 * lantern::ecs::detail::pod_map_bytes / sizeof(Pair);
    PodVector<Pair> v;
    bool crossed = false;
    for (std::uint64_t i = 0; i < large; ++i) {
        const bool was_mapped = v.mapped();
        v.push_back(Pair{i, ~i});
        crossed |= !was_mapped && v.mapped();
    }
#if defined(__linux__)
    EXPECT_TRUE(crossed);
    EXPECT_TRUE(v.mapped());
#endif
    for (std::uint64_t i = 0; i < large; ++i) ASSERT_TRUE(v[i].a == i && v[i].b == ~i) << i;
    PodVector<Pair> w;
    w.reserve(2 * large); // mapped straight from empty
    w.push_back(Pair{7, 7});
    EXPECT_EQ(w.mapped(), v.mapped());
    w = std::move(v); // unmaps w's own block
    EXPECT_EQ(v.data(), nullptr);
    EXPECT_FALSE(v.mapped());
    ASSERT_EQ(w.size(), large);
    EXPECT_EQ(w[large - 1].a, large - 1);
    PodVector<Pair> x(std::move(w));
    EXPECT_FALSE(w.mapped());
    EXPECT_EQ(x[12345].b, ~std::uint64_t(12345));
    x.resize(large + 10); // grows a mapped block; new elements value-initialised
    EXPECT_EQ(x[large + 9].a, 0u);
    EXPECT_EQ(x[large - 2].a, large - 2);
}

TEST(PodVector, PoolsUseItOnlyForTriviallyCopyableComponents) {
    static_assert(lantern::ecs::pod_vector_compatible<Pair>);
    static_assert(!lantern::ecs::pod_vector_compatible<std::string>);
    struct alignas(64) Wide {
        float v[16];
    };
    static_assert(!lantern::ecs::pod_vector_compatible<Wide>);
    // A pool of strings still works (std::vector storage) and one of Pairs too.
    lantern::ecs::Pool<std::string> strings;
    lantern::ecs::Pool<Pair> pairs;
    for (std::uint32_t i = 0; i < 5000; ++i) {
        strings.emplace({i, 0}, 1, std::string(40, char('a' + i % 26)));
        pairs.emplace({i, 0}, 1, Pair{i, i});
    }
    EXPECT_EQ(strings.get({4999, 0}), std::string(40, char('a' + 4999 % 26)));
    EXPECT_EQ(pairs.get({4999, 0}).a, 4999u);
    strings.erase_at(0, 2);
    EXPECT_EQ(strings.get({4999, 0}), std::string(40, char('a' + 4999 % 26)));
    EXPECT_EQ(strings.size(), 4999u);
}
