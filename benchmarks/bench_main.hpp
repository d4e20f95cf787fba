#pragma once

#include <atomic>
#include <string>
#include <thread>
#include <vector>

namespace lantern::bench {
// Lines printed before the benchmarks run (reference numbers to compare against).
std::vector<std::string>& reference_lines();

struct Reference {
    explicit Reference(std::initializer_list<const char*> lines) {
        for (const char* l : lines) reference_lines().emplace_back(l);
    }
};

// One busy loop per hardware thread for the object's lifetime: the contention the game's job
// workers see from lavapipe's own threads (issue 15). Benchmarks measure their quiet and
// contended rows in the same run.
class BusyCores {
  public:
    BusyCores();
    ~BusyCores();
    BusyCores(const BusyCores&) = delete;
    BusyCores& operator=(const BusyCores&) = delete;

  private:
    std::atomic<bool> stop_{false};
    std::vector<std::thread> threads_;
};
} // namespace lantern::bench
