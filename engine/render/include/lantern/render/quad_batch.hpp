// Batched screen-space quads (tiles, sprites, debug rectangles) drawn with one instanced draw:
// the simple 2D building block of the sandbox game's raster passes.
//
//   QuadBatch sprites = QuadBatch::create(device, {.color_format = target.color_format(),
//                                                  .depth_format = target.depth_format()});
//   sprites.clear();
//   sprites.add({.min = {16, 16}, .max = {32, 32}, .depth = 0.5f, .color = {1, 0, 0, 1}});
//   sprites.upload(cmd);                                // before the rendering scope
//   target.begin(cmd);
//   sprites.draw(cmd, target.extent(), &atlas);          // atlas: SHADER_READ_ONLY_OPTIMAL
//   target.end(cmd);
//
// Coordinates are target pixels (origin top-left, y down), so a quad from (x, y) to
// (x + 1, y + 1) covers exactly pixel (x, y). Colours are linear RGBA, stored as 8-bit and
// multiplied with the texture (nearest, clamped; a 1x1 white texture when none is given).
// With a depth format, quads are depth tested and written (0 near, 1 far; at equal depth the
// later quad wins); without, later quads draw over earlier ones.
//
// One texture per draw (use an atlas; several batches for several textures). The instance
// data is a StreamBuffer, so any number of frames may be in flight.
// Ownership: move-only; destroy before the Device. Threads: the recording thread.
#pragma once

#include "lantern/gpu/graphics_pipeline.hpp"
#include "lantern/gpu/image.hpp"
#include "lantern/render/stream_buffer.hpp"

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

namespace lantern::render {

struct Quad {
    glm::vec2 min{0.0f};    // top-left corner, target pixels
    glm::vec2 max{0.0f};    // bottom-right corner
    float depth = 0.0f;     // 0 (near) .. 1 (far)
    glm::vec4 color{1.0f};  // linear RGBA, 0..1
    glm::vec2 uv_min{0.0f}; // texture coordinates at min
    glm::vec2 uv_max{1.0f}; // and at max
};

struct QuadBatchDesc {
    VkFormat color_format = VK_FORMAT_UNDEFINED;
    VkFormat depth_format = VK_FORMAT_UNDEFINED; // UNDEFINED: no depth test
    gpu::BlendMode blend = gpu::BlendMode::alpha;
    std::uint32_t max_quads = 4096;
};

class QuadBatch {
  public:
    static QuadBatch create(gpu::Device& device, const QuadBatchDesc& desc);
    QuadBatch() = default;

    void clear();
    // At most max_quads per batch (asserted).
    void add(const Quad& quad);
    std::size_t size() const { return instances_.size(); }

    // Records the upload of the quads added since clear(); outside a rendering scope.
    void upload(gpu::CommandList& cmd);
    // Draws the uploaded quads inside a rendering scope with the desc's formats whose target
    // is `target` pixels large. `texture`: SAMPLED, in SHADER_READ_ONLY_OPTIMAL; nullptr
    // draws plain colours.
    void draw(gpu::CommandList& cmd, VkExtent2D target, const gpu::Image* texture = nullptr);

    // The per-quad vertex data (one instance): the layout render_quad.vert.glsl reads.
    struct Instance {
        float rect[4];       // min.x, min.y, max.x, max.y
        float uv[4];         // uv_min, uv_max
        std::uint32_t color; // RGBA8 UNORM
        float depth;
    };

  private:
    gpu::GraphicsPipeline pipeline_;
    gpu::Sampler sampler_;
    gpu::Image white_;
    StreamBuffer buffer_;
    std::vector<Instance> instances_;
    std::uint32_t max_quads_ = 0;
    std::size_t uploaded_ = 0; // instances in the buffer after the last upload
    bool dirty_ = false;       // added or cleared since the last upload
};

} // namespace lantern::render
