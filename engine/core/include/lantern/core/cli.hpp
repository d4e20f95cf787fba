// Command lines: the one parser behind every Lantern executable (lantern, lantern-render,
// lantern-bench, lantern-demo), so that all of them take options alike, answer --help and
// --version, and refuse bad input with one line and exit status 2.
//
//   cli::Parser p("lantern-demo", "[options]", "Simulates N agents with ECS systems ...");
//   p.integer("--frames", "N", "frames to run (default 300)", opt.frames, 1, 100000000);
//   p.flag("--quiet", "no progress output", opt.quiet);
//   if (auto exit = p.parse(argc, argv)) return *exit; // --help, --version or an error
//
// Options are "--name" (with "-h" for --help); a value is the next argument ("--frames 10")
// or follows '=' ("--frames=10"). An option given twice keeps the last value, except
// repeatable ones (each occurrence is passed on). Arguments that do not start with '-' are
// positionals. Messages: "<program>: --frames: expected an integer in [1, 100000000], got
// 'x' (see --help)"; quoted input is escaped and cut (core/text.hpp printable).
//
// Threads: a Parser is used from one thread; parse() may run once.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lantern::cli {

// "lantern 0.1.0": the project's version, as --version prints it after the program name.
std::string_view version();

class Parser {
  public:
    // `usage` follows the program name on the usage line ("SCENE.json [options]");
    // `about` is the paragraph under it.
    Parser(std::string program, std::string usage, std::string about);

    // A heading in --help for the options declared after it.
    Parser& section(std::string title);
    // Text printed at the end of --help (controls, exit statuses, examples).
    Parser& epilog(std::string text);

    // Checks a value: an error text ("must be on or off"), or nullopt to accept it.
    using Check = std::function<std::optional<std::string>(std::string_view value)>;

    // --name: sets `out` to true.
    Parser& flag(std::string name, std::string help, bool& out);
    // --name: runs `on` (e.g. sets an enum).
    Parser& flag(std::string name, std::string help, std::function<void()> on);
    // --name VALUE, a non-empty string.
    Parser& text(std::string name, std::string metavar, std::string help, std::string& out);
    // --name VALUE, one of `choices`.
    Parser& choice(std::string name, std::string help, std::string& out, std::vector<std::string> choices);
    // --name N, an integer in [min, max].
    Parser& integer(std::string name, std::string metavar, std::string help, int& out, int min, int max);
    // --name X, a finite number in [min, max].
    Parser& number(std::string name, std::string metavar, std::string help, double& out, double min, double max);
    Parser& number(std::string name, std::string metavar, std::string help, float& out, float min, float max);
    // --name VALUE handled by `on` (which returns an error text or nullopt). With
    // `optional_value`, a following argument that starts with '-' (or none) is not taken:
    // `on` then gets an empty view. With `repeatable`, every occurrence is handled.
    Parser& custom(std::string name, std::string metavar, std::string help, Check on, bool repeatable = false,
                   bool optional_value = false);
    // Arguments that are not options, in order: `on` gets each one (error text or nullopt).
    // Without a positional handler, any positional is an error.
    Parser& positionals(std::string metavar, std::string help, Check on);

    // Parses argv[first...]. Returns nullopt to go on; an exit status when the program
    // should stop: 0 after --help (printed on stdout) or --version, 2 after an error
    // (one line on stderr).
    std::optional<int> parse(int argc, const char* const* argv, int first = 1);
    std::optional<int> parse(int argc, char** argv, int first = 1) {
        return parse(argc, const_cast<const char* const*>(argv), first);
    }

    // Whether the last parse() met option `name` ("--name").
    bool given(std::string_view name) const;

    // The --help text.
    std::string help() const;
    // "<program>: <what> (see --help)": the one-line message parse() prints for `what`.
    std::string message(std::string_view what) const;

  private:
    struct Option {
        std::string name, metavar, help, section;
        bool takes_value = false;
        bool optional_value = false;
        bool repeatable = false;
        bool given = false;
        Check on;
    };
    Option& add(std::string name, std::string metavar, std::string help, bool takes_value, Check on);
    Option* find(std::string_view name);

    std::string program_, usage_, about_, epilog_, section_;
    std::vector<Option> options_;
    std::string positional_metavar_, positional_help_;
    Check positional_;
};

} // namespace lantern::cli
