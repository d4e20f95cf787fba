// lantern-bench: Lantern's benchmarks that need the GI pipeline (the ECS and job-system
// micro-benchmarks are Google Benchmark programs in benchmarks/).
//
//   lantern-bench seed-table [--repeats N] [--no-reference] [--row I] [--markdown FILE]
//   lantern-bench accuracy [--quick] [--repeats N] [--out DIR] [--scenes A,B] [--maps DIR]
//                          [--albedo A] [--target E] [--cache DIR | --no-cache] [--backend B]
//                          [--images]
#include "bench.hpp"

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

namespace {

constexpr const char* usage =
    "usage: lantern-bench seed-table [--repeats N] [--no-reference] [--row I] [--markdown FILE]\n"
    "                                [--block-h N] [--group-x N] [--group-y N]\n"
    "       lantern-bench accuracy [--quick] [--repeats N] [--out DIR] [--scenes A,B,...] [--maps DIR]\n"
    "                              [--albedo A] [--target E] [--cache DIR | --no-cache] [--backend vulkan|cpu]\n"
    "                              [--images]\n"
    "  seed-table  seed 000's performance table on this device: per-pass GPU time (timestamps,\n"
    "              median), each next to a copy kernel writing the same bytes, and the C++ reference\n"
    "  accuracy    error against run time: a sweep of GI settings on procedural scenes and real maps,\n"
    "              each timed (GPU timestamps, median) and compared with the light-transport reference;\n"
    "              writes DIR/accuracy.md, accuracy.csv and one plot per scene (default DIR: accuracy);\n"
    "              --images adds each scene's reference and Lantern images at Lantern's defaults\n";

int bad(const std::string& what) {
    std::fprintf(stderr, "lantern-bench: %s\n%s", what.c_str(), usage);
    return 2;
}

// Command-line cursor: the option at argv[i] and its values.
struct Args {
    int argc;
    char** argv;
    int i = 2;

    bool value(std::string& out) {
        if (i + 1 >= argc) return false;
        out = argv[++i];
        return true;
    }
    bool number(int& out, int lo, int hi) {
        std::string s;
        if (!value(s)) return false;
        char* end = nullptr;
        const long v = std::strtol(s.c_str(), &end, 10);
        if (s.empty() || *end || v < lo || v > hi) return false;
        out = int(v);
        return true;
    }
    bool real(double& out, double lo, double hi) {
        std::string s;
        if (!value(s)) return false;
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        if (s.empty() || *end || !(v >= lo && v <= hi)) return false;
        out = v;
        return true;
    }
};

int seed_table_main(Args a) {
    lantern::bench::SeedTableOptions o;
    for (; a.i < a.argc; ++a.i) {
        const std::string opt = a.argv[a.i];
        if (opt == "--no-reference") o.reference = false;
        else if (opt == "--repeats") { if (!a.number(o.repeats, 1, 1000)) return bad("--repeats needs 1..1000"); }
        else if (opt == "--row") { if (!a.number(o.only_row, 0, 1000)) return bad("--row needs a row index"); }
        else if (opt == "--block-h" || opt == "--group-x" || opt == "--group-y") {
            int v = 0;
            if (!a.number(v, 1, 64)) return bad(opt + " needs 1..64");
            (opt == "--block-h" ? o.block_h : opt == "--group-x" ? o.group_x : o.group_y) = unsigned(v);
        }
        else if (opt == "--markdown") { if (!a.value(o.markdown_out)) return bad("--markdown needs a file"); }
        else return bad("unknown option '" + opt + "'");
    }
    return lantern::bench::seed_table(o);
}

int accuracy_main(Args a) {
    lantern::bench::AccuracyOptions o;
    for (int k = 0; k < a.argc; ++k) o.command += (k ? " " : "") + std::string(a.argv[k]);
    for (; a.i < a.argc; ++a.i) {
        const std::string opt = a.argv[a.i];
        double v = 0.0;
        if (opt == "--quick") o.quick = true;
        else if (opt == "--no-cache") o.use_cache = false;
        else if (opt == "--images") o.images = true;
        else if (opt == "--repeats") { if (!a.number(o.repeats, 1, 1000)) return bad("--repeats needs 1..1000"); }
        else if (opt == "--out") { if (!a.value(o.out_dir)) return bad("--out needs a folder"); }
        else if (opt == "--maps") { if (!a.value(o.maps_dir)) return bad("--maps needs a folder"); }
        else if (opt == "--cache") { if (!a.value(o.cache_dir)) return bad("--cache needs a folder"); }
        else if (opt == "--albedo") {
            if (!a.real(v, 0.0, 1.0)) return bad("--albedo needs a value in [0, 1]");
            o.albedo = float(v);
        }
        else if (opt == "--target") { if (!a.real(o.target, 1e-4, 0.5)) return bad("--target needs a value in [0.0001, 0.5]"); }
        else if (opt == "--backend") {
            if (!a.value(o.backend) || (o.backend != "vulkan" && o.backend != "cpu")) return bad("--backend is vulkan or cpu");
        }
        else if (opt == "--scenes") {
            std::string list;
            if (!a.value(list)) return bad("--scenes needs names");
            std::stringstream ss(list);
            for (std::string name; std::getline(ss, name, ',');)
                if (!name.empty()) o.scenes.push_back(name);
        }
        else return bad("unknown option '" + opt + "'");
    }
    return lantern::bench::accuracy(o);
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 2 || std::string(argv[1]) == "--help") {
        std::fputs(usage, argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    const std::string command = argv[1];
    if (command == "seed-table") return seed_table_main(Args{argc, argv});
    if (command == "accuracy") return accuracy_main(Args{argc, argv});
    return bad("unknown command '" + command + "'");
}
