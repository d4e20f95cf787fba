// A one-line description of the machine a benchmark or tool ran on:
// CPU model, logical cores, memory, OS kernel and compiler. Benchmarks print it first.
#pragma once

#include <cstdint>
#include <string>

namespace lantern {

struct MachineInfo {
    std::string cpu_model;
    unsigned logical_cores = 0;
    double memory_gib = 0.0;
    std::string kernel;
    std::string compiler;
    std::string build_type;
};

MachineInfo machine_info();
std::string describe_machine();

// This process's resident set in bytes (Linux /proc/self/statm), 0 where it cannot be read.
// Soaks sample it to show that a long run does not grow.
std::uint64_t resident_set_bytes();

// Puts the calling thread at the lowest scheduling priority (Linux: nice 19 for this thread
// alone), so that it runs on the cores the frame and the Vulkan driver's threads leave idle:
// for background work no frame needs soon (the world baker). Not for work a later frame needs
// (the pipeline prefetch): a game running flat out leaves no idle core, and such a thread
// starves (docs/performance.md). Returns false where it could not (then the thread keeps its
// priority).
bool lower_thread_priority();

} // namespace lantern
