// Shared main for Lantern's Google Benchmark programs: prints the machine first, and an
// optional reference table a benchmark registers (numbers measured elsewhere to compare with).
#include "bench_main.hpp"

#include "lantern/core/machine.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>

namespace lantern::bench {

std::vector<std::string>& reference_lines() {
    static std::vector<std::string> lines;
    return lines;
}

BusyCores::BusyCores() {
    const unsigned n = std::max(1u, std::thread::hardware_concurrency());
    for (unsigned i = 0; i < n; ++i)
        threads_.emplace_back([this] {
            volatile std::uint64_t x = 0;
            while (!stop_.load(std::memory_order_relaxed)) x = x + 1;
        });
}

BusyCores::~BusyCores() {
    stop_.store(true);
    for (std::thread& t : threads_) t.join();
}

} // namespace lantern::bench

int main(int argc, char** argv) {
    std::printf("machine: %s\n", lantern::describe_machine().c_str());
    benchmark::AddCustomContext("lantern_machine", lantern::describe_machine());
    for (const auto& line : lantern::bench::reference_lines()) std::printf("%s\n", line.c_str());
    std::fflush(stdout);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
