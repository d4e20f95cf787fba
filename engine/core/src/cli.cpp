#include "lantern/core/cli.hpp"

#include "lantern/core/text.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>

#ifndef LANTERN_VERSION
#define LANTERN_VERSION "unknown"
#endif

namespace lantern::cli {

namespace {

constexpr std::size_t help_column = 24; // where option descriptions start in --help

std::string quote(std::string_view value) { return "'" + printable(value) + "'"; }

std::string format_bound(double v) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%g", v);
    return buf;
}

} // namespace

std::string_view version() { return "Lantern " LANTERN_VERSION; }

Parser::Parser(std::string program, std::string usage, std::string about)
    : program_(std::move(program)), usage_(std::move(usage)), about_(std::move(about)) {}

Parser& Parser::section(std::string title) {
    section_ = std::move(title);
    return *this;
}

Parser& Parser::epilog(std::string text) {
    epilog_ = std::move(text);
    return *this;
}

Parser::Option& Parser::add(std::string name, std::string metavar, std::string help, bool takes_value, Check on) {
    Option o;
    o.name = std::move(name);
    o.metavar = std::move(metavar);
    o.help = std::move(help);
    o.section = section_;
    o.takes_value = takes_value;
    o.on = std::move(on);
    options_.push_back(std::move(o));
    return options_.back();
}

Parser::Option* Parser::find(std::string_view name) {
    for (Option& o : options_)
        if (o.name == name) return &o;
    return nullptr;
}

Parser& Parser::flag(std::string name, std::string help, bool& out) {
    add(std::move(name), "", std::move(help), false, [&out](std::string_view) -> std::optional<std::string> {
        out = true;
        return std::nullopt;
    });
    return *this;
}

Parser& Parser::flag(std::string name, std::string help, std::function<void()> on) {
    add(std::move(name), "", std::move(help), false,
        [on = std::move(on)](std::string_view) -> std::optional<std::string> {
            on();
            return std::nullopt;
        });
    return *this;
}

Parser& Parser::text(std::string name, std::string metavar, std::string help, std::string& out) {
    add(std::move(name), std::move(metavar), std::move(help), true,
        [&out](std::string_view v) -> std::optional<std::string> {
            if (v.empty()) return "must not be empty";
            out = std::string(v);
            return std::nullopt;
        });
    return *this;
}

Parser& Parser::choice(std::string name, std::string help, std::string& out, std::vector<std::string> choices) {
    std::string metavar;
    for (std::size_t i = 0; i < choices.size(); ++i) metavar += (i ? "|" : "") + choices[i];
    add(std::move(name), metavar, std::move(help), true,
        [&out, choices = std::move(choices)](std::string_view v) -> std::optional<std::string> {
            for (const std::string& c : choices)
                if (c == v) {
                    out = c;
                    return std::nullopt;
                }
            std::string list;
            for (std::size_t i = 0; i < choices.size(); ++i)
                list += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + choices[i];
            return "must be " + list + ", got " + quote(v);
        });
    return *this;
}

Parser& Parser::integer(std::string name, std::string metavar, std::string help, int& out, int min, int max) {
    add(std::move(name), std::move(metavar), std::move(help), true,
        [&out, min, max](std::string_view v) -> std::optional<std::string> {
            long long n = 0;
            const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), n);
            if (v.empty() || ec != std::errc() || end != v.data() + v.size() || n < min || n > max)
                return "must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " +
                       quote(v);
            out = int(n);
            return std::nullopt;
        });
    return *this;
}

namespace {
// --name X: a finite number of type T in [min, max].
template <typename T>
Parser::Check number_check(T& out, T min, T max) {
    return [&out, min, max](std::string_view v) -> std::optional<std::string> {
        T x = 0;
        const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
        if (v.empty() || ec != std::errc() || end != v.data() + v.size() || !std::isfinite(x) || x < min || x > max)
            return "must be a number in [" + format_bound(double(min)) + ", " + format_bound(double(max)) + "], got " +
                   quote(v);
        out = x;
        return std::nullopt;
    };
}
} // namespace

Parser& Parser::number(std::string name, std::string metavar, std::string help, double& out, double min,
                       double max) {
    add(std::move(name), std::move(metavar), std::move(help), true, number_check(out, min, max));
    return *this;
}

Parser& Parser::number(std::string name, std::string metavar, std::string help, float& out, float min, float max) {
    add(std::move(name), std::move(metavar), std::move(help), true, number_check(out, min, max));
    return *this;
}

Parser& Parser::custom(std::string name, std::string metavar, std::string help, Check on, bool repeatable,
                       bool optional_value) {
    Option& o = add(std::move(name), std::move(metavar), std::move(help), true, std::move(on));
    o.repeatable = repeatable;
    o.optional_value = optional_value;
    return *this;
}

Parser& Parser::positionals(std::string metavar, std::string help, Check on) {
    positional_metavar_ = std::move(metavar);
    positional_help_ = std::move(help);
    positional_ = std::move(on);
    return *this;
}

std::string Parser::message(std::string_view what) const {
    return program_ + ": " + std::string(what) + " (see --help)";
}

std::optional<int> Parser::parse(int argc, const char* const* argv, int first) {
    auto fail = [&](const std::string& what) {
        std::fprintf(stderr, "%s\n", message(what).c_str());
        return std::optional<int>(2);
    };
    bool only_positionals = false;
    for (int i = first; i < argc; ++i) {
        const std::string_view arg = argv[i] ? argv[i] : "";
        const bool option_like = !only_positionals && arg.size() > 1 && arg[0] == '-';
        if (!option_like) {
            if (!positional_) return fail("unexpected argument " + quote(arg));
            if (auto problem = positional_(arg)) return fail(*problem);
            continue;
        }
        if (arg == "--") {
            only_positionals = true;
            continue;
        }
        if (arg == "--help" || arg == "-h") {
            std::fputs(help().c_str(), stdout);
            return 0;
        }
        if (arg == "--version") {
            std::printf("%s (%s)\n", program_.c_str(), std::string(version()).c_str());
            return 0;
        }
        const std::size_t equals = arg.find('=');
        const std::string_view name = arg.substr(0, equals);
        Option* o = name.starts_with("--") ? find(name) : nullptr;
        if (!o) return fail("unknown option " + quote(name));
        std::string_view value;
        if (equals != std::string_view::npos) {
            if (!o->takes_value) return fail(std::string(name) + " takes no value");
            value = arg.substr(equals + 1);
        } else if (o->takes_value) {
            const bool next_is_value = i + 1 < argc && argv[i + 1] &&
                                       !(o->optional_value && argv[i + 1][0] == '-' && argv[i + 1][1] != '\0');
            if (next_is_value) value = argv[++i];
            else if (!o->optional_value) return fail(std::string(name) + " needs a value (" + o->metavar + ")");
        }
        o->given = true;
        if (auto problem = o->on(value)) return fail(std::string(name) + ": " + *problem);
    }
    return std::nullopt;
}

bool Parser::given(std::string_view name) const {
    for (const Option& o : options_)
        if (o.name == name) return o.given;
    return false;
}

std::string Parser::help() const {
    std::ostringstream out;
    out << "usage: " << program_ << (usage_.empty() ? "" : " ") << usage_ << "\n";
    if (!about_.empty()) out << "\n" << about_ << (about_.ends_with('\n') ? "" : "\n");
    auto line = [&](const std::string& left, const std::string& help) {
        std::string head = "  " + left;
        if (head.size() + 1 > help_column) {
            out << head << "\n";
            head.clear();
        }
        head.resize(help_column, ' ');
        std::istringstream lines(help);
        std::string text;
        bool first_line = true;
        while (std::getline(lines, text)) {
            out << (first_line ? head : std::string(help_column, ' ')) << text << "\n";
            first_line = false;
        }
        if (first_line) out << head << "\n";
    };
    if (positional_ && !positional_help_.empty()) {
        out << "\n";
        line(positional_metavar_, positional_help_);
    }
    std::string current = "\x01"; // no section printed yet
    for (const Option& o : options_) {
        if (o.section != current) {
            out << "\n" << (o.section.empty() ? "options" : o.section) << "\n";
            current = o.section;
        }
        std::string left = o.name;
        if (o.takes_value) left += o.optional_value ? " [" + o.metavar + "]" : " " + o.metavar;
        line(left, o.help + (o.repeatable ? " (repeatable)" : ""));
    }
    out << "\n";
    line("-h, --help", "this help");
    line("--version", "the program and Lantern's version");
    if (!epilog_.empty()) out << "\n" << epilog_ << (epilog_.ends_with('\n') ? "" : "\n");
    return out.str();
}

} // namespace lantern::cli
