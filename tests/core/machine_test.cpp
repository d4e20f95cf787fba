// lantern/core/machine.hpp: the machine line's parts and the background threads' priority.
#include "lantern/core/machine.hpp"

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <thread>

namespace {

int this_thread_priority() { return getpriority(PRIO_PROCESS, id_t(syscall(SYS_gettid))); }

} // namespace

// A thread that lowers its priority runs at nice 19 from then on; the thread that started it
// keeps its own (the frame's threads must not be slowed along with the world baker).
TEST(Machine, LowerThreadPriorityLowersOnlyTheCallingThread) {
    const int before = this_thread_priority();
    int in_thread = -100, after_call = -100;
    bool lowered = false;
    std::thread t([&] {
        in_thread = this_thread_priority();
        lowered = lantern::lower_thread_priority();
        after_call = this_thread_priority();
    });
    t.join();
    EXPECT_EQ(in_thread, before); // a new thread starts at its creator's
    ASSERT_TRUE(lowered);
    EXPECT_EQ(after_call, 19);
    EXPECT_EQ(this_thread_priority(), before);
}

TEST(Machine, DescribesTheMachine) {
    const lantern::MachineInfo info = lantern::machine_info();
    EXPECT_GE(info.logical_cores, 1u);
    EXPECT_GT(info.memory_gib, 0.0);
    EXPECT_NE(lantern::describe_machine().find("logical core"), std::string::npos) << lantern::describe_machine();
    EXPECT_GT(lantern::resident_set_bytes(), 0u);
}
