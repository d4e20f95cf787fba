#include "lantern/core/result.hpp"

#include <gtest/gtest.h>

#include <memory>

using lantern::Error;
using lantern::Result;

namespace {
Result<int> parse_positive(int v) {
    if (v <= 0) return lantern::make_error("scene.json:3:7: radius must be positive");
    return v;
}
} // namespace

TEST(Result, HoldsValueOrError) {
    auto good = parse_positive(4);
    ASSERT_TRUE(good.ok());
    EXPECT_EQ(*good, 4);
    auto bad = parse_positive(-1);
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().message, "scene.json:3:7: radius must be positive");
    EXPECT_EQ(bad.error().exit_code, 2);
}

TEST(Result, MovesOnlyTypes) {
    Result<std::unique_ptr<int>> r(std::make_unique<int>(7));
    ASSERT_TRUE(r.ok());
    std::unique_ptr<int> p = std::move(r).value();
    EXPECT_EQ(*p, 7);
}

TEST(Result, VoidResult) {
    Result<void> ok;
    EXPECT_TRUE(ok.ok());
    Result<void> bad = Error{"nope", 1};
    EXPECT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().exit_code, 1);
}

TEST(ResultDeathTest, ValueOfErrorAsserts) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    auto bad = parse_positive(0);
    EXPECT_DEATH((void)bad.value(), "value\\(\\) of a failed Result");
}
