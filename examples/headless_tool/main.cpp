// headless_tool: a tool of its own built against the installed Lantern (docs/extending.md).
// Loads a scene file into an ECS world, steps the frame systems N frames on the C++
// reference backend (no GPU needed) and writes the last frame's lit image as a PNG.
//
//   headless_tool SCENE.json [--frames N] [--out IMAGE.png]
#include "lantern/core/cli.hpp"
#include "lantern/core/png.hpp"
#include "lantern/gi/backend.hpp"
#include "lantern/jobs/job_system.hpp"
#include "lantern/scene/loader.hpp"
#include "lantern/systems/scene_world.hpp"

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    using namespace lantern;
    std::string scene_path, out = "out.png";
    int frames = 1;
    cli::Parser p("headless_tool", "SCENE.json [options]", "Steps a scene's world and writes the lit image.");
    p.positionals("SCENE.json", "the scene file", [&](std::string_view v) -> std::optional<std::string> {
        scene_path = std::string(v);
        return std::nullopt;
    });
    p.integer("--frames", "N", "frames to step (default 1)", frames, 1, 10000);
    p.text("--out", "IMAGE.png", "the lit image (default out.png)", out);
    if (auto exit = p.parse(argc, argv)) return *exit;
    auto scene = scene::load_scene(scene_path);
    if (!scene) {
        std::fprintf(stderr, "headless_tool: %s\n", scene.error().message.c_str());
        return scene.error().exit_code;
    }
    jobs::JobSystem jobs;
    ecs::World world;
    systems::SceneWorld sw = systems::populate_world(*scene, world);
    sw.config.lit_image = true;
    systems::GiFrame frame(world, jobs, sw.source, gi::make_reference_backend(&jobs), sw.config);
    frame.warm_up();
    for (int k = 0; k < frames; ++k) {
        const systems::FrameReport report = frame.step();
        if (report.error) {
            std::fprintf(stderr, "headless_tool: %s\n", report.error->message.c_str());
            return report.error->exit_code;
        }
    }
    frame.backend().wait_idle();
    const std::optional<gi::Image> lit = frame.backend().read_lit();
    if (!lit) {
        std::fprintf(stderr, "headless_tool: no lit image\n");
        return 1;
    }
    if (auto ok = write_png(out, lit->width, lit->height, 3, lit->rgb); !ok) {
        std::fprintf(stderr, "headless_tool: %s\n", ok.error().message.c_str());
        return 1;
    }
    std::printf("headless_tool: %d frames, %d x %d texels -> %s\n", frames, lit->width, lit->height, out.c_str());
    return 0;
}
