// A one-line description of the machine a benchmark or tool ran on:
// CPU model, logical cores, memory, OS kernel and compiler. Benchmarks print it first.
#pragma once

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

} // namespace lantern
