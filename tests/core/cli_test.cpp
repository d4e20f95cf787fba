// cli::Parser: values in both spellings, optional and repeated values, positionals, one-line
// errors with exit 2, --help and --version with exit 0.
#include "lantern/core/cli.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace lantern {
namespace {

struct Parsed {
    std::optional<int> exit;
    std::string out, err;
};

Parsed parse(cli::Parser& p, std::vector<const char*> args) {
    args.insert(args.begin(), "prog");
    testing::internal::CaptureStdout();
    testing::internal::CaptureStderr();
    Parsed r;
    r.exit = p.parse(int(args.size()), args.data());
    r.out = testing::internal::GetCapturedStdout();
    r.err = testing::internal::GetCapturedStderr();
    return r;
}

struct Values {
    int n = 1;
    double x = 0.5;
    bool quiet = false;
    std::string mode = "a", file;
    std::vector<std::string> sets, positionals;
    std::optional<std::string> seed;
};

cli::Parser make(Values& v) {
    cli::Parser p("prog", "[options] FILE...", "Does things.");
    p.section("numbers");
    p.integer("--n", "N", "a count", v.n, 1, 10);
    p.number("--x", "X", "a fraction\nover two lines", v.x, 0.0, 1.0);
    p.section("other");
    p.flag("--quiet", "no output", v.quiet);
    p.choice("--mode", "how", v.mode, {"a", "b", "c"});
    p.text("--file", "PATH", "a file", v.file);
    p.custom("--set", "K=V", "a setting", [&](std::string_view s) -> std::optional<std::string> {
        if (s.find('=') == std::string_view::npos) return "must be KEY=VALUE";
        v.sets.emplace_back(s);
        return std::nullopt;
    }, true);
    p.custom("--seed", "S", "a seed", [&](std::string_view s) -> std::optional<std::string> {
        v.seed = std::string(s);
        return std::nullopt;
    }, false, true);
    p.positionals("FILE", "inputs", [&](std::string_view s) -> std::optional<std::string> {
        v.positionals.emplace_back(s);
        return std::nullopt;
    });
    return p;
}

TEST(Cli, ValuesBothSpellingsRepeatsAndPositionals) {
    Values v;
    cli::Parser p = make(v);
    const Parsed r = parse(p, {"--n", "7", "--x=0.25", "in1", "--quiet", "--mode", "c", "--set", "a=1", "--set=b=2",
                              "--seed", "--file", "f.txt", "--", "--not-an-option"});
    EXPECT_FALSE(r.exit) << r.err;
    EXPECT_EQ(v.n, 7);
    EXPECT_EQ(v.x, 0.25);
    EXPECT_TRUE(v.quiet);
    EXPECT_EQ(v.mode, "c");
    EXPECT_EQ(v.file, "f.txt");
    EXPECT_EQ(v.sets, (std::vector<std::string>{"a=1", "b=2"}));
    EXPECT_EQ(v.seed, std::string()); // optional value: the next argument is an option
    EXPECT_EQ(v.positionals, (std::vector<std::string>{"in1", "--not-an-option"}));
}

TEST(Cli, ErrorsAreOneLineWithExitTwo) {
    const std::vector<std::pair<std::vector<const char*>, std::string>> cases = {
        {{"--n", "11"}, "prog: --n: must be an integer in [1, 10], got '11' (see --help)\n"},
        {{"--n", "3x"}, "prog: --n: must be an integer in [1, 10], got '3x' (see --help)\n"},
        {{"--n", "99999999999999999999"},
         "prog: --n: must be an integer in [1, 10], got '99999999999999999999' (see --help)\n"},
        {{"--x", "nan"}, "prog: --x: must be a number in [0, 1], got 'nan' (see --help)\n"},
        {{"--x", "1e400"}, "prog: --x: must be a number in [0, 1], got '1e400' (see --help)\n"},
        {{"--mode", "d"}, "prog: --mode: must be a, b or c, got 'd' (see --help)\n"},
        {{"--file", ""}, "prog: --file: must not be empty (see --help)\n"},
        {{"--file"}, "prog: --file needs a value (PATH) (see --help)\n"},
        {{"--quiet=1"}, "prog: --quiet takes no value (see --help)\n"},
        {{"--set", "x"}, "prog: --set: must be KEY=VALUE (see --help)\n"},
        {{"--nope\n\x01"}, "prog: unknown option '--nope\\n\\x01' (see --help)\n"},
        {{"-x"}, "prog: unknown option '-x' (see --help)\n"},
    };
    for (const auto& [args, expect] : cases) {
        Values v;
        cli::Parser p = make(v);
        const Parsed r = parse(p, args);
        EXPECT_EQ(r.exit, 2) << expect;
        EXPECT_EQ(r.err, expect);
        EXPECT_EQ(r.out, "");
    }
    cli::Parser no_positionals("prog", "", "");
    const Parsed r = parse(no_positionals, {"stray"});
    EXPECT_EQ(r.exit, 2);
    EXPECT_EQ(r.err, "prog: unexpected argument 'stray' (see --help)\n");
}

TEST(Cli, HelpAndVersion) {
    Values v;
    cli::Parser p = make(v);
    p.epilog("exit status: 0 ok, 2 bad input");
    const Parsed help = parse(p, {"--n", "3", "-h", "--bogus"}); // stops at -h
    EXPECT_EQ(help.exit, 0);
    EXPECT_EQ(help.err, "");
    EXPECT_EQ(help.out, p.help());
    EXPECT_EQ(help.out, "usage: prog [options] FILE...\n"
                        "\n"
                        "Does things.\n"
                        "\n"
                        "  FILE                  inputs\n"
                        "\n"
                        "numbers\n"
                        "  --n N                 a count\n"
                        "  --x X                 a fraction\n"
                        "                        over two lines\n"
                        "\n"
                        "other\n"
                        "  --quiet               no output\n"
                        "  --mode a|b|c          how\n"
                        "  --file PATH           a file\n"
                        "  --set K=V             a setting (repeatable)\n"
                        "  --seed [S]            a seed\n"
                        "\n"
                        "  -h, --help            this help\n"
                        "  --version             the program and Lantern's version\n"
                        "\n"
                        "exit status: 0 ok, 2 bad input\n");
    Values w;
    cli::Parser q = make(w);
    const Parsed version = parse(q, {"--version"});
    EXPECT_EQ(version.exit, 0);
    EXPECT_EQ(version.out, "prog (" + std::string(cli::version()) + ")\n");
    EXPECT_EQ(std::string(cli::version()).rfind("Lantern 0.", 0), 0u);
}

} // namespace
} // namespace lantern
