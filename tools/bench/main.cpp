// lantern-bench: Lantern's benchmarks that need the GI pipeline (the ECS and job-system
// micro-benchmarks are Google Benchmark programs in benchmarks/).
//
//   lantern-bench seed-table [--repeats N] [--no-reference] [--row I] [--markdown FILE]
#include "bench.hpp"

#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

constexpr const char* usage =
    "usage: lantern-bench seed-table [--repeats N] [--no-reference] [--row I] [--markdown FILE]\n"
    "                                [--block-h N] [--group-x N] [--group-y N]\n"
    "  seed-table  seed 000's performance table on this device: per-pass GPU time (timestamps,\n"
    "              median), each next to a copy kernel writing the same bytes, and the C++ reference\n";

int bad(const std::string& what) {
    std::fprintf(stderr, "lantern-bench: %s\n%s", what.c_str(), usage);
    return 2;
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 2 || std::string(argv[1]) == "--help") {
        std::fputs(usage, argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    const std::string command = argv[1];
    if (command != "seed-table") return bad("unknown command '" + command + "'");
    lantern::bench::SeedTableOptions o;
    for (int i = 2; i < argc; ++i) {
        const std::string a = argv[i];
        auto number = [&](int& out) {
            if (i + 1 >= argc) return false;
            char* end = nullptr;
            long v = std::strtol(argv[++i], &end, 10);
            if (*end || v < 0 || v > 1000) return false;
            out = int(v);
            return true;
        };
        if (a == "--no-reference") o.reference = false;
        else if (a == "--repeats") { if (!number(o.repeats) || o.repeats == 0) return bad("--repeats needs 1..1000"); }
        else if (a == "--row") { if (!number(o.only_row)) return bad("--row needs a row index"); }
        else if (a == "--block-h" || a == "--group-x" || a == "--group-y") {
            int v = 0;
            if (!number(v) || v == 0 || v > 64) return bad(a + " needs 1..64");
            (a == "--block-h" ? o.block_h : a == "--group-x" ? o.group_x : o.group_y) = unsigned(v);
        }
        else if (a == "--markdown") { if (i + 1 >= argc) return bad("--markdown needs a file"); o.markdown_out = argv[++i]; }
        else return bad("unknown option '" + a + "'");
    }
    return lantern::bench::seed_table(o);
}
