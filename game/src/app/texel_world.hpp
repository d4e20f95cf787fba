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
#include "lantern/game/game_components.hpp"
#include "lantern/game/world_renderer.hpp"
#include "lantern/gi/frame_inputs.hpp"
#include "lantern/texel/pass_table.hpp"
#include "lantern/texel/texel.hpp"
#include "lantern/texel/vulkan/texel_passes.hpp"

#include <memory>
#include <span>
#include <vector>

namespace lantern::game {

enum class TexelModel : int {
    player_body,
    player_head,
    backpack,
    tree_trunk,
    tree_crown,
    lamp_post,
    torch_stick,
    crystal,       // a crystal's tall shard (it glows: TexelPart::glow)
    crystal_shard, // and the small one beside it
    // Dropped items (DroppedItem), small: a block of rock, a torch, a crystal, a lamp post's
    // head, a sapling.
    item_block,
    item_torch,
    item_crystal,
    item_lamp_post,
    item_sapling,
    count
};

inline constexpr int texel_density = 8; // texels per world unit of the models' art (LOD 0)
// Levels of detail: LOD k paints the model at texel_density >> k texels per unit, so a far
// model's light costs a quarter per level. A part whose centre is farther than
// texel_lod_distance tiles (on the ground) from the point the camera looks at takes LOD 1.
inline constexpr int texel_lod_count = 2;
inline constexpr float texel_lod_distance = 9.0f;
int texel_lod_for(glm::vec3 center, glm::vec2 view_target);

// The model a dropped item is drawn as.
TexelModel item_model(Item item);

// The half extents of a model's box (the draw list's box for it has these).
glm::vec3 texel_model_half(TexelModel model);
// The model at a level of detail, its pixel-art albedo and normal map (made once, on first
// use; thread-safe). The same box at every level; the art coarser.
const texel::Model& texel_model(TexelModel model, int lod = 0);

class TexelWorld {
  public:
    static Result<std::unique_ptr<TexelWorld>> create(gpu::Device& device);

    // Records this frame's texel passes into `cmd` for `parts` (the draw list's) under
    // `lights`, the walls from `walls` (the GI's view of them; none: open ground), as the
    // texel pass table plans them (last_plan()), each row between `timer`'s marks. Lights
    // marked texel::as_baked are baked for the still parts when they, the layout, the walls
    // or a still part change (bakes()), and lit live on parts that move (TexelPart::moves).
    void record(gpu::CommandList& cmd, std::span<const TexelPart> parts, std::span<const texel::TexelLight> lights,
                const gi::WallView& walls, float wall_height, texel::vk::TexelRowTimer* timer = nullptr);

    // The draw list's parts' records (same order), and the buffers the raster reads.
    std::span<const TexelRecord> records() const { return records_; }
    // How many times the static lights were baked so far.
    std::uint64_t bakes() const { return bakes_; }
    // What the last record() ran, and why the rest did not.
    const texel::TexelPlan& last_plan() const { return last_plan_; }
    const gpu::Buffer& lit() const { return passes_->lit(); }
    const gpu::Buffer& surfaces() const { return passes_->surfaces(); }
    const gpu::Buffer& albedo() const { return passes_->albedo(); }

  private:
    explicit TexelWorld(std::unique_ptr<texel::vk::TexelPasses> passes) : passes_(std::move(passes)) {}
    std::unique_ptr<texel::vk::TexelPasses> passes_;
    texel::TexelHistory history_;
    texel::TexelPlan last_plan_;
    std::uint64_t bakes_ = 0;
    std::vector<TexelRecord> records_;
    std::vector<std::uint32_t> order_; // the parts in atlas order: still ones, then moving ones
    std::vector<glm::vec4> albedo_;
};

} // namespace lantern::game
