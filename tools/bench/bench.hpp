// lantern-bench subcommands.
#pragma once

#include <string>

namespace lantern::bench {

struct SeedTableOptions {
    int repeats = 5;         // measured frames per row (after one warm-up)
    bool reference = true;   // also time the C++ reference (single thread; slow)
    int only_row = -1;       // run one row of the table (0-based), -1 = all
    std::string markdown_out; // also write the summary table here
    unsigned block_h = 0, group_x = 0, group_y = 0; // 0: the renderer's default for the device
};
int seed_table(const SeedTableOptions& options);

} // namespace lantern::bench
