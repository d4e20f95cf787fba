// Exits 0 when the embedded shader library looks right: the known shader has SPIR-V words
// starting with the magic number, an unknown name gives an empty span, the names list it.
#include "good_shaders.hpp"

#include <cstdio>

int main() {
    const auto words = good_shaders_spirv("good.comp");
    const auto names = good_shaders_names();
    const bool ok = words.size() > 5 && words[0] == 0x07230203u && good_shaders_spirv("nope.comp").empty() &&
                    names.size() == 1 && names[0] == "good.comp";
    std::printf("good.comp: %zu words, %s\n", words.size(), ok ? "ok" : "WRONG");
    return ok ? 0 : 1;
}
