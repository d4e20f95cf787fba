// The game's per-texel lit models (docs/texel.md, "In the game"): the player's body, head and
// backpack, trees' trunks and crowns, lamp posts and torch sticks are texel_lit boxes whose
// light the texel passes compute once per texel of their pixel-art texture (generated here,
// no binary assets), then the world renderer draws them texel by texel.
//
//   build_draw_list   emits a texel_lit box and a TexelPart per part, and the frame's lights
//   TexelWorld        per frame: the scene rebuilt when the parts in view change (UV to world
//                     again for parts that moved), the light pass, the records for the raster
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/game/world_renderer.hpp"
#include "lantern/gi/frame_inputs.hpp"
#include "lantern/texel/texel.hpp"
#include "lantern/texel/vulkan/texel_passes.hpp"

#include <memory>
#include <span>
#include <vector>

namespace lantern::game {

enum class TexelModel : int { player_body, player_head, backpack, tree_trunk, tree_crown, lamp_post, torch_stick, count };

inline constexpr int texel_density = 8; // texels per world unit of the models' art

// The half extents of a model's box (the draw list's box for it has these).
glm::vec3 texel_model_half(TexelModel model);
// The model, its pixel-art albedo and normal map (made once, on first use; thread-safe).
const texel::Model& texel_model(TexelModel model);

class TexelWorld {
  public:
    static Result<std::unique_ptr<TexelWorld>> create(gpu::Device& device);

    // Records this frame's texel passes into `cmd` for `parts` (the draw list's) under
    // `lights`, the walls from `walls` (the GI's view of them; none: open ground).
    void record(gpu::CommandList& cmd, std::span<const TexelPart> parts, std::span<const texel::TexelLight> lights,
                const gi::WallView& walls, float wall_height);

    // The draw list's parts' records (same order), and the buffers the raster reads.
    std::span<const TexelRecord> records() const { return records_; }
    const gpu::Buffer& lit() const { return passes_->lit(); }
    const gpu::Buffer& surfaces() const { return passes_->surfaces(); }
    const gpu::Buffer& albedo() const { return passes_->albedo(); }

  private:
    explicit TexelWorld(std::unique_ptr<texel::vk::TexelPasses> passes) : passes_(std::move(passes)) {}
    std::unique_ptr<texel::vk::TexelPasses> passes_;
    texel::TexelScene scene_;
    std::vector<TexelPart> last_parts_;
    std::vector<TexelRecord> records_;
    std::vector<glm::vec4> albedo_;
};

} // namespace lantern::game
