// libFuzzer target: the game's tables file (--tables). Tables that parse are written again and
// read back: they must read, and read as the same tables.
#include "lantern/game/tables.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    auto tables = lantern::game::parse_tables(text, "fuzz.json");
    if (tables) {
        auto again = lantern::game::parse_tables(lantern::game::format_tables(*tables), "again.json");
        if (!again || !(*again == *tables)) std::abort(); // what Lantern writes must read back the same
    }
    return 0;
}
