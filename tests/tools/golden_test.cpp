// Golden images: the eight scenes in tests/golden/, rendered by lantern-render on both
// backends, against the committed PNGs (regenerate: bash scripts/update-goldens.sh).
// Tolerance: at most 3 sRGB steps on any channel and a mean under 0.5 step, so math-library
// differences between machines pass while any change of the lighting itself does not.
#include "common/test_support.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <sys/wait.h>

#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

namespace fs = std::filesystem;

namespace {

struct Pixels {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;
};

Pixels load_png(const fs::path& path) {
    Pixels p;
    int channels = 0;
    std::unique_ptr<unsigned char, void (*)(void*)> data(stbi_load(path.c_str(), &p.width, &p.height, &channels, 3),
                                                         stbi_image_free);
    if (data) p.rgb.assign(data.get(), data.get() + std::size_t(p.width) * std::size_t(p.height) * 3);
    return p;
}

int render(const fs::path& scene, const fs::path& out, const char* backend, std::string& output) {
    const std::string cmd = std::string(LANTERN_RENDER_EXE) + " " + scene.string() + " --quiet --backend " + backend +
                            " --out " + out.string() + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    char buf[1024];
    std::size_t n;
    while ((n = fread(buf, 1, sizeof(buf), p)) > 0) output.append(buf, n);
    const int status = pclose(p);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

class Golden : public ::testing::TestWithParam<std::string> {};

} // namespace

TEST_P(Golden, MatchesOnBothBackends) {
    const fs::path dir = lantern::test::source_dir() / "tests" / "golden";
    const fs::path scene = dir / (GetParam() + ".json");
    const Pixels golden = load_png(dir / (GetParam() + ".png"));
    ASSERT_FALSE(golden.rgb.empty()) << "missing golden image for " << GetParam();
    lantern::test::TempDir tmp;
    for (const char* backend : {"cpu", "vulkan"}) {
        std::string output;
        const int status = render(scene, tmp.path() / "out.png", backend, output);
        if (status == 1 && output.find("no Vulkan device") != std::string::npos) {
            std::printf("[  SKIPPED ] vulkan backend: %s", output.c_str());
            continue;
        }
        ASSERT_EQ(status, 0) << backend << ": " << output;
        const Pixels got = load_png(tmp.path() / "out.png");
        ASSERT_EQ(got.width, golden.width) << backend;
        ASSERT_EQ(got.height, golden.height) << backend;
        int worst = 0;
        double sum = 0.0;
        for (std::size_t i = 0; i < golden.rgb.size(); ++i) {
            const int d = std::abs(int(got.rgb[i]) - int(golden.rgb[i]));
            worst = std::max(worst, d);
            sum += d;
        }
        EXPECT_LE(worst, 3) << GetParam() << " on " << backend;
        EXPECT_LT(sum / double(golden.rgb.size()), 0.5) << GetParam() << " on " << backend;
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, Golden,
                         ::testing::Values("torch_rooms", "crystal_cave", "courtyard_sun", "corridor_quarter",
                                           "dusk_camera", "warm_faces", "seed000_options", "flat_walls"),
                         [](const auto& p) { return p.param; });
