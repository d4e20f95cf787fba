// libFuzzer target: the save loader. A save that parses is written again and read back:
// formatting what was read must give a save that reads.
#include "lantern/game/save.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    auto save = lantern::game::parse_save(text, "fuzz.json");
    if (save) {
        auto again = lantern::game::parse_save(lantern::game::format_save(*save), "again.json");
        if (!again) std::abort(); // a save Lantern wrote must read
    }
    return 0;
}
