#include "moving_ai_map.hpp"

#include "lantern/scene/json_reader.hpp"
#include "lantern/core/file.hpp"
#include "lantern/core/text.hpp"
#include "lantern/scene/loader.hpp"

#include <algorithm>
#include <array>
#include <charconv>

namespace lantern::scene {
namespace {

constexpr std::string_view moving_ai_chars = ".GSW@OT";
// Line numbers are ints; the largest map allowed (2^28 cells) is far smaller.
constexpr std::size_t max_map_bytes = 0x7FFFFFFF;

enum class Cell : std::uint8_t { unknown, floor, wall, tree };

std::array<Cell, 256> cell_table(const MapImportOptions& options) {
    std::array<Cell, 256> table{};
    auto set = [&](char c, Cell cell) { table[static_cast<unsigned char>(c)] = cell; };
    for (char c : std::string_view(".GSW")) set(c, Cell::floor);
    set('@', Cell::wall);
    set('O', Cell::wall);
    set('T', Cell::tree);
    for (char c : options.extra_floor_chars) set(c, Cell::floor);
    return table;
}

// Splits text into lines ended by "\n" or "\r\n" and numbers them from 1.
class LineReader {
  public:
    explicit LineReader(std::string_view text) : text_(text) {}

    // The next line without its line end (LF, CRLF or a lone CR), or false at the end of
    // the text. Either way line_number() is then the number of that line (one past the
    // last at the end).
    bool next(std::string_view& line) {
        ++line_number_;
        if (pos_ >= text_.size()) return false;
        const std::size_t end = std::min(text_.find_first_of("\r\n", pos_), text_.size());
        line = text_.substr(pos_, end - pos_);
        pos_ = end + 1;
        if (end < text_.size() && text_[end] == '\r' && pos_ < text_.size() && text_[pos_] == '\n') ++pos_; // CRLF
        return true;
    }
    int line_number() const { return line_number_; }

  private:
    std::string_view text_;
    std::size_t pos_ = 0;
    int line_number_ = 0;
};

Error map_error(const std::string& file, int line, std::size_t column, const std::string& what) {
    return make_error(file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " +
                      what);
}

// Reads the header line "<keyword> N" with N in [1, max_grid_side].
Result<int> read_header_number(LineReader& lines, std::string_view keyword,
                               const std::string& file) {
    std::string_view line;
    const bool found = lines.next(line);
    const std::string expected =
        "expected '" + std::string(keyword) + " N' with N in 1.." + std::to_string(max_grid_side);
    if (!found)
        return map_error(file, lines.line_number(), 1, expected + ", found the end of the file");
    int value = 0;
    const std::string_view digits = line.substr(std::min(line.size(), keyword.size() + 1));
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    const bool valid = line.starts_with(keyword) && line.size() > keyword.size() &&
                       line[keyword.size()] == ' ' && ec == std::errc() &&
                       end == digits.data() + digits.size() && value >= 1 && value <= max_grid_side;
    if (!valid)
        return map_error(file, lines.line_number(), 1,
                         expected + ", got '" + reading::shorten(line) + "'");
    return value;
}

Result<void> expect_header_line(LineReader& lines, std::string_view expected,
                                const std::string& file) {
    std::string_view line;
    const bool found = lines.next(line);
    if (found && line == expected) return {};
    return map_error(
        file, lines.line_number(), 1,
        "expected '" + std::string(expected) + "' (Moving AI map header), " +
            (found ? "got '" + reading::shorten(line) + "'" : "found the end of the file"));
}

// "type octile", "height H", "width W", "map": the grid size (W, H).
Result<glm::ivec2> read_header(LineReader& lines, const std::string& file) {
    if (auto type = expect_header_line(lines, "type octile", file); !type) return type.error();
    auto height = read_header_number(lines, "height", file);
    if (!height) return height.error();
    auto width = read_header_number(lines, "width", file);
    if (!width) return width.error();
    if (std::int64_t(*width) * *height > max_grid_cells)
        return map_error(file, lines.line_number(), 1,
                         "a map of " + std::to_string(*width) + " x " + std::to_string(*height) +
                             " cells is above the limit of " + std::to_string(max_grid_cells) +
                             " cells");
    if (auto map = expect_header_line(lines, "map", file); !map) return map.error();
    return glm::ivec2(*width, *height);
}

Error unknown_char_error(const std::string& file, int line, std::string_view row, std::size_t at) {
    // The column counts characters (code points), as in scene files.
    std::size_t column = 1;
    for (std::size_t i = 0; i < at;) {
        const std::size_t n = utf8_char(row.substr(i));
        i += n ? n : 1;
        ++column;
    }
    return map_error(file, line, column,
                     "unknown map character " + reading::quote_char_at(row, at) +
                         " (the Moving AI format has . G S W @ O T; list it in the scene's "
                         "world.extra_floor_chars to read it as floor)");
}

// One map row: its cells appended to the grid, its trees to the tree list. An unknown
// character is reported before a wrong length, and nothing is stored for a bad row.
Result<void> read_row(std::string_view line, int line_number, int row,
                      const std::array<Cell, 256>& table, const MapImportOptions& options,
                      const std::string& file, ImportedMap& map) {
    auto cell_of = [&](char c) { return table[static_cast<unsigned char>(c)]; };
    const auto unknown =
        std::find_if(line.begin(), line.end(), [&](char c) { return cell_of(c) == Cell::unknown; });
    if (unknown != line.end())
        return unknown_char_error(file, line_number, line, std::size_t(unknown - line.begin()));
    const std::size_t width = std::size_t(map.walls.width);
    if (line.size() != width)
        return map_error(file, line_number, std::min(line.size(), width) + 1,
                         "row has " + std::to_string(line.size()) + " characters, expected " +
                             std::to_string(width) + " (the header's width)");
    for (std::size_t col = 0; col < width; ++col) {
        const Cell cell = cell_of(line[col]);
        if (cell == Cell::tree && options.trees == TreeMode::proxy) {
            if (std::int64_t(map.trees.size()) == max_map_tree_proxies)
                return map_error(file, line_number, col + 1,
                                 "more than " + std::to_string(max_map_tree_proxies) +
                                     " trees ('T' cells), the limit for trees as shadow proxies "
                                     "(each costs memory; docs/scenes.md, \"Size limits\")");
            map.trees.emplace_back(int(col), row);
        }
        const bool wall =
            cell == Cell::wall || (cell == Cell::tree && options.trees == TreeMode::wall);
        map.walls.cells.push_back(wall ? 1 : 0);
    }
    return {};
}

Result<void> read_rows(LineReader& lines, const MapImportOptions& options, const std::string& file,
                       ImportedMap& map) {
    const std::array<Cell, 256> table = cell_table(options);
    std::string_view line;
    for (int row = 0; row < map.walls.height; ++row) {
        if (!lines.next(line))
            return map_error(file, lines.line_number(), 1,
                             "expected " + std::to_string(map.walls.height) +
                                 " rows (the header's height), found " + std::to_string(row));
        if (auto read = read_row(line, lines.line_number(), row, table, options, file, map); !read)
            return read.error();
    }
    while (lines.next(line))
        if (!line.empty())
            return map_error(file, lines.line_number(), 1,
                             "more than " + std::to_string(map.walls.height) +
                                 " rows (the header's height)");
    return {};
}

} // namespace

namespace reading {

std::optional<std::string> extra_floor_chars_problem(std::string_view chars) {
    for (char c : chars) {
        if (c <= ' ' || c > '~') return quote_char(c) + " is not a printable ASCII character";
        if (moving_ai_chars.find(c) != std::string_view::npos)
            return quote_char(c) + " already has a meaning in Moving AI maps (. G S W @ O T)";
    }
    return std::nullopt;
}

} // namespace reading

Result<ImportedMap> parse_moving_ai_map(std::string_view text, const std::string& file_name,
                                        const MapImportOptions& options) {
    if (auto problem = reading::extra_floor_chars_problem(options.extra_floor_chars))
        return make_error("extra_floor_chars: " + *problem);
    if (text.size() >= max_map_bytes)
        return make_error(file_name + ": larger than " + std::to_string(max_map_bytes) + " bytes");
    // A UTF-8 byte order mark is skipped, as the JSON reader skips it (editors add one).
    if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
    LineReader lines(text);
    auto size = read_header(lines, file_name);
    if (!size) return size.error();
    ImportedMap map;
    map.walls.width = size->x;
    map.walls.height = size->y;
    // Bounded by the text size as well, so a lying header cannot reserve gigabytes.
    map.walls.cells.reserve(std::min(std::size_t(size->x) * std::size_t(size->y), text.size()));
    if (auto rows = read_rows(lines, options, file_name, map); !rows) return rows.error();
    return map;
}

Result<ImportedMap> import_moving_ai_map(const std::string& path, const MapImportOptions& options) {
    auto text = read_text_file(path, max_map_file_bytes);
    if (!text) return make_error(text.error().message); // exit code 2: a bad input path
    return parse_moving_ai_map(*text, path, options);
}

} // namespace lantern::scene
