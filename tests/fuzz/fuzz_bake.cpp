// libFuzzer target: the bake's chunk cache files (lantern/bake/bake.hpp decode_chunk). A file
// that decodes is encoded again: that must give back the same bytes.
#include "lantern/bake/bake.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    auto chunk = lantern::bake::decode_chunk(std::span<const std::uint8_t>(data, size));
    if (chunk) {
        const std::vector<std::byte> again = lantern::bake::encode_chunk(*chunk);
        if (again.size() != size || std::memcmp(again.data(), data, size) != 0) std::abort();
    }
    return 0;
}
