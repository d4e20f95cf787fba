#include "accuracy_metrics.hpp"

#include "lantern/gi/shading.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace lantern::bench {
namespace {

constexpr glm::vec3 rec709(0.2126f, 0.7152f, 0.0722f);

// Reference texels that are compared: air, centre inside the visible view.
std::vector<std::uint8_t> compared_texels(const transport::TransportResult& ref,
                                          const scene::Scene& s) {
    const gi::GiWindow& w = ref.window;
    std::vector<std::uint8_t> mask(std::size_t(w.width) * std::size_t(w.height), 0);
    const auto area = gi::visible_area(s.view);
    if (!area) return mask;
    for (int y = 0; y < w.height; ++y)
        for (int x = 0; x < w.width; ++x) {
            const glm::vec2 p = w.texel_center(x, y);
            const bool visible = p.x >= area->min.x && p.y >= area->min.y &&
                                 p.x < area->min.x + area->size.x &&
                                 p.y < area->min.y + area->size.y;
            if (visible && !s.walls.is_wall_tile(int(std::floor(p.x)), int(std::floor(p.y))))
                mask[std::size_t(y) * std::size_t(w.width) + std::size_t(x)] = 1;
        }
    return mask;
}

const gi::Texture* texture(const gi::FrameResult& f, const char* name) {
    auto it = f.textures.find(name);
    return it == f.textures.end() ? nullptr : &it->second;
}

glm::vec3 texel_rgb(const gi::Texture& t, const gi::GiWindow& w, glm::vec2 p) {
    const int x =
        std::clamp(int(std::floor((p.x - w.view.min_x) * float(w.resolution))), 0, w.width - 1);
    const int y =
        std::clamp(int(std::floor((p.y - w.view.min_z) * float(w.resolution))), 0, w.height - 1);
    const float* v = t.at(x, y);
    return {v[0], v[1], v[2]};
}

// Sums for a relative RMSE with and without the exposure fit.
struct ErrorSums {
    double diff2 = 0.0, ref2 = 0.0, cross = 0.0, lantern2 = 0.0;
    void add(glm::vec3 l, glm::vec3 r) {
        for (int c = 0; c < 3; ++c) {
            diff2 += double(l[c] - r[c]) * double(l[c] - r[c]);
            ref2 += double(r[c]) * r[c];
            cross += double(l[c]) * r[c];
            lantern2 += double(l[c]) * l[c];
        }
    }
    double rmse() const { return ref2 > 0.0 ? std::sqrt(diff2 / ref2) : 0.0; }
    double scale() const { return lantern2 > 0.0 ? cross / lantern2 : 0.0; }
    double rmse_fit() const {
        const double s = scale();
        return ref2 > 0.0
                   ? std::sqrt(std::max(0.0, s * s * lantern2 - 2.0 * s * cross + ref2) / ref2)
                   : 0.0;
    }
};

float display_luma(glm::vec3 linear, const scene::GiSettings& gi) {
    const glm::vec3 mapped = gi::tone_map(linear, gi.tone_map, gi.white_point);
    const glm::vec3 srgb(gi::linear_to_srgb8(mapped.r), gi::linear_to_srgb8(mapped.g),
                         gi::linear_to_srgb8(mapped.b));
    return glm::dot(srgb / 255.0f, rec709);
}

// Separable Gaussian (sigma 1.5, 11 taps) of an image; taps outside it count as zero (the
// normalised convolution divides the same weights out of the mask).
std::vector<double> gaussian_blur(const std::vector<double>& in, int w, int h) {
    static const std::array<double, 11> kernel = [] {
        std::array<double, 11> k{};
        for (int i = 0; i < 11; ++i)
            k[std::size_t(i)] = std::exp(-double((i - 5) * (i - 5)) / (2.0 * 1.5 * 1.5));
        return k;
    }();
    std::vector<double> tmp(in.size(), 0.0), out(in.size(), 0.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = -5; k <= 5; ++k)
                if (x + k >= 0 && x + k < w)
                    tmp[std::size_t(y * w + x)] +=
                        kernel[std::size_t(k + 5)] * in[std::size_t(y * w + x + k)];
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = -5; k <= 5; ++k)
                if (y + k >= 0 && y + k < h)
                    out[std::size_t(y * w + x)] +=
                        kernel[std::size_t(k + 5)] * tmp[std::size_t((y + k) * w + x)];
    return out;
}

// Mean SSIM over the masked texels, local statistics by normalised convolution.
double masked_ssim(const std::vector<double>& a, const std::vector<double>& b,
                   const std::vector<std::uint8_t>& mask, int w, int h) {
    const std::size_t n = a.size();
    std::vector<double> m(n), ma(n), mb(n), maa(n), mbb(n), mab(n);
    for (std::size_t i = 0; i < n; ++i) {
        m[i] = mask[i];
        ma[i] = m[i] * a[i], mb[i] = m[i] * b[i];
        maa[i] = ma[i] * a[i], mbb[i] = mb[i] * b[i], mab[i] = ma[i] * b[i];
    }
    const auto wm = gaussian_blur(m, w, h), wa = gaussian_blur(ma, w, h),
               wb = gaussian_blur(mb, w, h);
    const auto waa = gaussian_blur(maa, w, h), wbb = gaussian_blur(mbb, w, h),
               wab = gaussian_blur(mab, w, h);
    constexpr double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    double sum = 0.0;
    int count = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (!mask[i]) continue;
        const double mu_a = wa[i] / wm[i], mu_b = wb[i] / wm[i];
        const double var_a = std::max(0.0, waa[i] / wm[i] - mu_a * mu_a),
                     var_b = std::max(0.0, wbb[i] / wm[i] - mu_b * mu_b);
        const double cov = wab[i] / wm[i] - mu_a * mu_b;
        sum += ((2.0 * mu_a * mu_b + c1) * (2.0 * cov + c2)) /
               ((mu_a * mu_a + mu_b * mu_b + c1) * (var_a + var_b + c2));
        ++count;
    }
    return count ? sum / count : 0.0;
}

} // namespace

namespace {

// Lantern's and the reference's light at one compared texel.
struct Sample {
    std::size_t texel; // y * width + x on the reference grid
    glm::vec3 lantern_total, lantern_direct, reference_direct, reference_indirect;
};

std::vector<Sample> samples(const transport::TransportResult& ref, const gi::FrameInputs& in,
                            const gi::FrameResult& frame, const std::vector<std::uint8_t>& mask) {
    const gi::GiWindow& w = ref.window;
    gi::ShadingInputs shading;
    shading.frame = &in;
    shading.direct = texture(frame, "direct");
    shading.indirect = texture(frame, "indirect");
    shading.shadow = texture(frame, "shadow");
    std::vector<Sample> out;
    for (int y = 0; y < w.height; ++y)
        for (int x = 0; x < w.width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(w.width) + std::size_t(x);
            if (!mask[i]) continue;
            const glm::vec2 p = w.texel_center(x, y);
            out.push_back(
                {i, gi::surface_light(shading, {p.x, 0.0f, p.y}, {0.0f, 1.0f, 0.0f}),
                 shading.direct ? texel_rgb(*shading.direct, in.window, p) : glm::vec3(0.0f),
                 ref.direct.at(x, y), ref.indirect.at(x, y)});
        }
    return out;
}

} // namespace

ErrorMetrics compare_to_reference(const transport::TransportResult& ref, const scene::Scene& scene,
                                  const gi::FrameInputs& in, const gi::FrameResult& frame) {
    const gi::GiWindow& w = ref.window;
    const std::vector<std::uint8_t> mask = compared_texels(ref, scene);
    ErrorSums total, indirect, shadow;
    double max_diff = 0.0, max_ref = 0.0;
    std::vector<double> lantern_luma(mask.size(), 0.0), ref_luma(mask.size(), 0.0);
    ErrorMetrics m;
    for (const Sample& s : samples(ref, in, frame, mask)) {
        const glm::vec3 r_total = s.reference_direct + s.reference_indirect;
        total.add(s.lantern_total, r_total);
        indirect.add(s.lantern_total - s.lantern_direct, s.reference_indirect);
        if (s.reference_direct == glm::vec3(0.0f)) {
            shadow.add(s.lantern_total, r_total);
            ++m.shadow_texels;
        }
        max_diff =
            std::max(max_diff, double(std::abs(glm::dot(s.lantern_total - r_total, rec709))));
        max_ref = std::max(max_ref, double(glm::dot(r_total, rec709)));
        lantern_luma[s.texel] = display_luma(s.lantern_total, scene.gi);
        ref_luma[s.texel] = display_luma(r_total, scene.gi);
        ++m.texels;
    }
    m.total_rmse = total.rmse(), m.total_rmse_fit = total.rmse_fit(), m.total_scale = total.scale();
    m.indirect_rmse = indirect.rmse(), m.indirect_rmse_fit = indirect.rmse_fit(),
    m.indirect_scale = indirect.scale();
    m.shadow_rmse_fit = shadow.rmse_fit();
    m.max_error = max_ref > 0.0 ? max_diff / max_ref : 0.0;
    m.ssim = masked_ssim(lantern_luma, ref_luma, mask, w.width, w.height);
    return m;
}

ViewImages view_images(const transport::TransportResult& ref, const scene::Scene& scene,
                       const gi::FrameInputs& in, const gi::FrameResult& frame) {
    const gi::GiWindow& w = ref.window;
    const auto area = gi::visible_area(scene.view);
    ViewImages img;
    if (!area) return img;
    // Texels whose centres lie in the view: centre = min + (i + 0.5) / res.
    const float res = float(w.resolution);
    const int x0 = int(std::ceil((area->min.x - w.view.min_x) * res - 0.5f));
    const int x1 = int(std::ceil((area->min.x + area->size.x - w.view.min_x) * res - 0.5f));
    const int y0 = int(std::ceil((area->min.y - w.view.min_z) * res - 0.5f));
    const int y1 = int(std::ceil((area->min.y + area->size.y - w.view.min_z) * res - 0.5f));
    img.width = x1 - x0, img.height = y1 - y0;
    img.reference.assign(std::size_t(img.width) * std::size_t(img.height) * 3, 0x60);
    img.lantern = img.reference;
    auto put = [&](std::vector<std::uint8_t>& image, std::size_t texel, glm::vec3 linear) {
        const int x = int(texel % std::size_t(w.width)) - x0,
                  y = int(texel / std::size_t(w.width)) - y0;
        const glm::vec3 mapped = gi::tone_map(linear, scene.gi.tone_map, scene.gi.white_point);
        std::uint8_t* p =
            &image[(std::size_t(img.height - 1 - y) * std::size_t(img.width) + std::size_t(x)) * 3];
        p[0] = gi::linear_to_srgb8(mapped.r), p[1] = gi::linear_to_srgb8(mapped.g),
        p[2] = gi::linear_to_srgb8(mapped.b);
    };
    for (const Sample& s : samples(ref, in, frame, compared_texels(ref, scene))) {
        put(img.reference, s.texel, s.reference_direct + s.reference_indirect);
        put(img.lantern, s.texel, s.lantern_total);
    }
    return img;
}

ReferenceNoise reference_noise(const transport::TransportResult& ref, const scene::Scene& scene) {
    const std::vector<std::uint8_t> mask = compared_texels(ref, scene);
    double se2 = 0.0, indirect2 = 0.0, total2 = 0.0;
    ReferenceNoise n;
    for (int y = 0; y < ref.window.height; ++y)
        for (int x = 0; x < ref.window.width; ++x) {
            if (!mask[std::size_t(y) * std::size_t(ref.window.width) + std::size_t(x)]) continue;
            const glm::vec3 se = ref.indirect_error.at(x, y), ind = ref.indirect.at(x, y),
                            tot = ind + ref.direct.at(x, y);
            se2 += double(glm::dot(se, se));
            indirect2 += double(glm::dot(ind, ind));
            total2 += double(glm::dot(tot, tot));
            ++n.texels;
        }
    n.indirect = indirect2 > 0.0 ? std::sqrt(se2 / indirect2) : 0.0;
    n.total = total2 > 0.0 ? std::sqrt(se2 / total2) : 0.0;
    return n;
}

} // namespace lantern::bench
