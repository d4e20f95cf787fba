#include "lantern/jobs/deque.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

using lantern::jobs::WorkStealingDeque;

TEST(WorkStealingDeque, OwnerIsLifoThiefIsFifo) {
    WorkStealingDeque<int, 8> d;
    int items[4] = {0, 1, 2, 3};
    for (int& i : items) ASSERT_TRUE(d.push(&i));
    EXPECT_EQ(d.steal(), &items[0]);
    EXPECT_EQ(d.pop(), &items[3]);
    EXPECT_EQ(d.pop(), &items[2]);
    EXPECT_EQ(d.steal(), &items[1]);
    EXPECT_EQ(d.pop(), nullptr);
    EXPECT_EQ(d.steal(), nullptr);
    EXPECT_TRUE(d.empty_hint());
}

TEST(WorkStealingDeque, PushFailsWhenFullAndRecovers) {
    WorkStealingDeque<int, 4> d;
    int items[5] = {};
    for (int i = 0; i < 4; ++i) ASSERT_TRUE(d.push(&items[i]));
    EXPECT_FALSE(d.push(&items[4]));
    EXPECT_EQ(d.steal(), &items[0]);
    EXPECT_TRUE(d.push(&items[4])); // wraps around the ring
    EXPECT_EQ(d.pop(), &items[4]);
    EXPECT_EQ(d.pop(), &items[3]);
}

TEST(WorkStealingDeque, EveryItemTakenExactlyOnceUnderContention) {
    constexpr int n = 200000;
    WorkStealingDeque<int, 1024> d;
    std::vector<int> items(n);
    std::vector<std::atomic<int>> taken(n);
    std::atomic<bool> done{false};
    auto take = [&](int* p) { taken[p - items.data()].fetch_add(1, std::memory_order_relaxed); };
    std::vector<std::thread> thieves;
    for (int t = 0; t < 3; ++t)
        thieves.emplace_back([&] {
            while (!done.load(std::memory_order_acquire))
                if (int* p = d.steal()) take(p);
        });
    int next = 0;
    while (next < n) {
        if (d.push(&items[next])) {
            ++next;
            if (next % 3 == 0)
                if (int* p = d.pop()) take(p);
        } else if (int* p = d.pop()) {
            take(p);
        }
    }
    while (int* p = d.pop()) take(p);
    // Thieves may still hold one item each in flight; wait until all are accounted for.
    auto total = [&] {
        long s = 0;
        for (auto& t : taken) s += t.load();
        return s;
    };
    while (total() < n) std::this_thread::yield();
    done.store(true, std::memory_order_release);
    for (auto& t : thieves) t.join();
    for (int i = 0; i < n; ++i) ASSERT_EQ(taken[i].load(), 1) << "item " << i;
}
