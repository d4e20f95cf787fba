#pragma once

#include <string>
#include <vector>

namespace lantern::bench {
// Lines printed before the benchmarks run (reference numbers to compare against).
std::vector<std::string>& reference_lines();

struct Reference {
    explicit Reference(std::initializer_list<const char*> lines) {
        for (const char* l : lines) reference_lines().emplace_back(l);
    }
};
} // namespace lantern::bench
