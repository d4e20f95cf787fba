// How wrong a Lantern frame is against the transport reference (docs/accuracy.md,
// "Metrics").
//
// Compared texels: the reference's air texels whose centres lie in the visible view (the
// unpadded camera rectangle: padding exists to hide the window edge, so nobody sees it).
// Lantern's light at a reference texel is what its shading library returns there
// (gi::surface_light for the ground, without AO: the flatland reference has no height
// for contact shadows), i.e. direct + indirect + directional bounce of the Lantern texel
// containing the reference texel's centre: a coarser Lantern grid is compared as the
// player sees it, block by block. Lantern's indirect is that minus its direct texture.
#pragma once

#include "lantern/gi/frame_runner.hpp"
#include "lantern/transport/solver.hpp"

namespace lantern::bench {

struct ErrorMetrics {
    // Relative RMSE sqrt(sum (L - R)^2 / sum R^2) over compared texels and RGB channels,
    // unfitted and after the least-squares exposure fit L -> s L, s = sum L R / sum L^2
    // (fitted separately for total and for indirect light; the fitted s is reported).
    double total_rmse = 0.0, total_rmse_fit = 0.0, total_scale = 0.0;
    double indirect_rmse = 0.0, indirect_rmse_fit = 0.0, indirect_scale = 0.0;
    // The same after a fit of its own, over the texels the reference gives no direct light:
    // how well light that turned a corner is modelled (0 without such texels).
    double shadow_rmse_fit = 0.0;
    int shadow_texels = 0;
    // max |Y_L - Y_R| over compared texels / max Y_R, Y = Rec. 709 luminance of total light.
    double max_error = 0.0;
    // Mean SSIM of the tone-mapped images (the scene's tone map, sRGB-encoded, Rec. 709 luma
    // Y'), Gaussian window sigma 1.5 texels truncated at 11 x 11, C1 = 0.01^2, C2 = 0.03^2,
    // with the local statistics taken over compared texels only (normalised convolution).
    double ssim = 0.0;
    int texels = 0;
};

// The reference's own noise over the same texels: relative standard error of indirect and
// of total light (sqrt(sum SE^2) / sqrt(sum R^2)), the floor below which the relative RMSE
// above cannot be trusted.
struct ReferenceNoise {
    double indirect = 0.0, total = 0.0;
    int texels = 0;
};

// `frame` must hold Lantern's "direct", "indirect" and "shadow" textures for `in`.
ErrorMetrics compare_to_reference(const transport::TransportResult& ref, const scene::Scene& scene,
                                  const gi::FrameInputs& in, const gi::FrameResult& frame);
ReferenceNoise reference_noise(const transport::TransportResult& ref, const scene::Scene& scene);

// The visible view seen from above at the reference resolution, as the comparison sees it:
// ground texels show total light, tone-mapped and sRGB-encoded; walls are mid grey. RGB8,
// north (max z) at the top.
struct ViewImages {
    int width = 0, height = 0;
    std::vector<std::uint8_t> reference, lantern;
};
ViewImages view_images(const transport::TransportResult& ref, const scene::Scene& scene,
                       const gi::FrameInputs& in, const gi::FrameResult& frame);

} // namespace lantern::bench
