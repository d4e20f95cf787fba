// Submissions in flight, serials, and deferred destruction. A host-signalled timeline
// semaphore ("gate") holds a submission on the GPU until the test opens it, so "still in
// flight" is deterministic instead of a race against a fast device.
#include "gpu/gpu_test_support.hpp"

#include "lantern/gpu/device.hpp"
#include "lantern/gpu/vk_check.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace gpu = lantern::gpu;
using lantern::test::read_back_as;

namespace {

// A timeline semaphore at 0; submissions given wait() run once open() set it to 1.
class Gate {
  public:
    explicit Gate(gpu::Device& device) : device_(device) {
        VkSemaphoreTypeCreateInfo type{};
        type.sType = VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO;
        type.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
        VkSemaphoreCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;
        info.pNext = &type;
        VK_CHECK(vkCreateSemaphore(device.vk_device(), &info, nullptr, &semaphore_));
        wait_ = {semaphore_, 1, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT};
    }
    ~Gate() {
        open();
        device_.wait_idle();
        vkDestroySemaphore(device_.vk_device(), semaphore_, nullptr);
    }
    Gate(const Gate&) = delete;
    Gate& operator=(const Gate&) = delete;

    gpu::SubmitInfo wait() const { return {.waits = {&wait_, 1}}; }
    void open() {
        if (opened_) return;
        opened_ = true;
        VkSemaphoreSignalInfo signal{};
        signal.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SIGNAL_INFO;
        signal.semaphore = semaphore_;
        signal.value = 1;
        VK_CHECK(vkSignalSemaphore(device_.vk_device(), &signal));
    }

  private:
    gpu::Device& device_;
    VkSemaphore semaphore_ = VK_NULL_HANDLE;
    gpu::SemaphoreWait wait_;
    bool opened_ = false;
};

class Submission : public lantern::test::GpuTest {
  protected:
    gpu::Buffer storage(std::uint32_t words, const char* name) {
        return device().create_buffer({words * 4u, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                       gpu::MemoryKind::device_local, name});
    }
    std::uint64_t submit_fill(const gpu::Buffer& buffer, std::uint32_t value, const gpu::SubmitInfo& info = {}) {
        gpu::CommandList cmd = device().begin("fill");
        cmd.fill_buffer(buffer, value);
        return device().submit(std::move(cmd), info);
    }
};

} // namespace

TEST_F(Submission, SerialsIncreaseAndCompleteInOrder) {
    gpu::Buffer buffer = storage(64, "serials");
    const std::uint64_t first = submit_fill(buffer, 1);
    const std::uint64_t second = submit_fill(buffer, 2);
    EXPECT_EQ(second, first + 1);
    EXPECT_EQ(device().last_submitted_serial(), second);
    device().wait(second);
    EXPECT_TRUE(device().is_complete(first));
    EXPECT_EQ(device().completed_serial(), second);
    EXPECT_EQ(device().submissions_in_flight(), 0u);
}

TEST_F(Submission, TwoSubmissionsInFlight) {
    gpu::Buffer a = storage(256, "a");
    gpu::Buffer b = storage(256, "b");
    Gate gate(device());
    const std::uint64_t before = device().completed_serial();
    const std::uint64_t first = submit_fill(a, 0x11111111u, gate.wait());
    const std::uint64_t second = submit_fill(b, 0x22222222u);
    EXPECT_EQ(device().submissions_in_flight(), 2u);
    EXPECT_EQ(device().completed_serial(), before); // the gate holds the first, hence both
    EXPECT_FALSE(device().is_complete(first));

    gate.open();
    device().wait(second);
    EXPECT_TRUE(device().is_complete(first));
    EXPECT_EQ(device().submissions_in_flight(), 0u);
    EXPECT_EQ(read_back_as<std::uint32_t>(device(), a), std::vector<std::uint32_t>(256, 0x11111111u));
    EXPECT_EQ(read_back_as<std::uint32_t>(device(), b), std::vector<std::uint32_t>(256, 0x22222222u));
}

TEST_F(Submission, DestroyedWhileInFlightIsFreedOnlyAfterCompletion) {
    device().collect();
    ASSERT_EQ(device().pending_deletions(), 0u);
    Gate gate(device());
    gpu::Buffer buffer = storage(1024, "in flight");
    const std::uint64_t serial = submit_fill(buffer, 7, gate.wait());
    buffer.reset();
    EXPECT_EQ(device().pending_deletions(), 1u);
    device().collect();
    EXPECT_EQ(device().pending_deletions(), 1u); // still in use by the held submission
    EXPECT_FALSE(device().is_complete(serial));

    gate.open();
    device().wait(serial);
    EXPECT_EQ(device().pending_deletions(), 0u);
}

TEST_F(Submission, DestroyedWhileRecordedWaitsForThatList) {
    device().collect();
    Gate gate(device());
    gpu::Buffer buffer = storage(1024, "recorded");
    gpu::CommandList cmd = device().begin("records a destroyed buffer");
    cmd.fill_buffer(buffer, 9);
    buffer.reset(); // destroyed while the list that uses it is still being recorded
    device().collect();
    EXPECT_EQ(device().pending_deletions(), 1u);

    // A list submitted in between does not release it: the recording list has not run yet.
    gpu::Buffer other = storage(16, "other");
    const std::uint64_t unrelated = submit_fill(other, 1);
    device().wait(unrelated);
    EXPECT_EQ(device().pending_deletions(), 1u);

    const std::uint64_t serial = device().submit(std::move(cmd), gate.wait());
    device().collect();
    EXPECT_EQ(device().pending_deletions(), 1u);
    gate.open();
    device().wait(serial);
    EXPECT_EQ(device().pending_deletions(), 0u);
}

TEST_F(Submission, DiscardedListSubmitsNothingAndReleasesWhatItHeld) {
    const std::uint64_t submitted = device().last_submitted_serial();
    gpu::Buffer buffer = storage(64, "discarded");
    {
        gpu::CommandList cmd = device().begin("discarded");
        cmd.fill_buffer(buffer, 3);
        buffer.reset();
        EXPECT_EQ(device().pending_deletions(), 1u);
    } // dropped unsubmitted
    EXPECT_EQ(device().last_submitted_serial(), submitted);
    device().collect();
    EXPECT_EQ(device().pending_deletions(), 0u);
}

TEST_F(Submission, ContextsAreRecycledAcrossManySubmissions) {
    gpu::Buffer buffer = storage(64, "recycle");
    std::uint64_t last = 0;
    for (std::uint32_t i = 0; i < 20; ++i) {
        last = submit_fill(buffer, i);
        if (i % 4 == 3) device().wait(last);
    }
    device().wait(last);
    EXPECT_EQ(device().submissions_in_flight(), 0u);
    EXPECT_EQ(read_back_as<std::uint32_t>(device(), buffer), std::vector<std::uint32_t>(64, 19u));
}
