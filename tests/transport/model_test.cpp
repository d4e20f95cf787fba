// The physical model's source terms: analytic answers, agreement with Lantern's direct
// pass, and the importance-sampling bound.
#include "transport_test_util.hpp"

#include "lantern/gi/reference.hpp"
#include "lantern/transport/model.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <random>

namespace {

using namespace lantern;
using transport::FaceRef;
using transport::SourceKind;

std::vector<std::string> open_rows() {
    return std::vector<std::string>(16, std::string(16, '.'));
}

gi::FrameInputs inputs_of(const scene::Scene& s, int resolution) {
    auto window = gi::compute_window(s.view, s.gi.padding, resolution);
    EXPECT_TRUE(window.has_value());
    return gi::gather_frame_inputs(s, *window);
}

TEST(Model, FaceGeometry) {
    const FaceRef px{{3, 5}, gi::face_pos_x}, nx{{3, 5}, gi::face_neg_x},
        pz{{3, 5}, gi::face_pos_z}, nz{{3, 5}, gi::face_neg_z};
    EXPECT_EQ(transport::face_normal(gi::face_pos_x), glm::vec2(1, 0));
    EXPECT_EQ(transport::face_normal(gi::face_neg_x), glm::vec2(-1, 0));
    EXPECT_EQ(transport::face_normal(gi::face_pos_z), glm::vec2(0, 1));
    EXPECT_EQ(transport::face_normal(gi::face_neg_z), glm::vec2(0, -1));
    EXPECT_EQ(transport::face_point(px, 0.25f), glm::vec2(4.0f, 5.25f));
    EXPECT_EQ(transport::face_point(nx, 0.25f), glm::vec2(3.0f, 5.25f));
    EXPECT_EQ(transport::face_point(pz, 0.25f), glm::vec2(3.25f, 6.0f));
    EXPECT_EQ(transport::face_point(nz, 0.25f), glm::vec2(3.25f, 5.0f));

    auto rows = open_rows();
    rows[5][3] = rows[5][4] = '#'; // two walls side by side: the face between is buried
    const scene::Scene s = transport_test::scene(rows, {8, 8}, {16, 16});
    const gi::FrameInputs in = inputs_of(s, 4);
    EXPECT_FALSE(transport::face_exposed(in.walls, px));
    EXPECT_TRUE(transport::face_exposed(in.walls, nx));
    EXPECT_TRUE(transport::face_exposed(in.walls, pz));
    EXPECT_FALSE(transport::face_exposed(in.walls, FaceRef{{2, 5}, gi::face_pos_x})); // not a wall
}

TEST(Model, UnoccludedPointLightFollowsTheFalloff) {
    for (float softness : {1.0f, 2.5f}) {
        scene::Scene s = transport_test::scene(open_rows(), {8, 8}, {16, 16});
        s.gi.light_softness = softness;
        s.point_lights.push_back({{8.3f, 7.6f}, 1.0f, {1.0f, 0.6f, 0.3f}, 2.0f, 6.0f});
        const gi::FrameInputs in = inputs_of(s, 4);
        for (float x = 0.1f; x < 16.0f; x += 0.37f)
            for (float z = 0.2f; z < 16.0f; z += 0.41f) {
                const double d = std::hypot(double(x) - 8.3, double(z) - 7.6);
                const double f = d < 6.0 ? 2.0 * std::pow(1.0 - d / 6.0, double(softness)) : 0.0;
                const glm::vec3 got = transport::direct_fluence(in, {x, z});
                EXPECT_NEAR(got.r, f * 1.0, 1e-5 + 1e-5 * f) << x << ", " << z;
                EXPECT_NEAR(got.g, f * 0.6, 1e-5 + 1e-5 * f);
                EXPECT_NEAR(got.b, f * 0.3, 1e-5 + 1e-5 * f);
            }
    }
}

TEST(Model, FaceIrradianceIsFluenceTimesCosine) {
    auto rows = open_rows();
    rows[4][8] = '#';
    scene::Scene s = transport_test::scene(rows, {8, 8}, {16, 16});
    s.point_lights.push_back({{10.0f, 7.0f}, 1.0f, {1.0f, 1.0f, 1.0f}, 1.0f, 8.0f});
    const gi::FrameInputs in = inputs_of(s, 4);
    const FaceRef top{{8, 4}, gi::face_pos_z}, bottom{{8, 4}, gi::face_neg_z};
    for (float t : {0.1f, 0.5f, 0.9f}) {
        const glm::vec2 p = transport::face_point(top, t);
        const glm::vec2 to_light = glm::vec2(10.0f, 7.0f) - p;
        const float d = glm::length(to_light);
        const float expected = (1.0f - d / 8.0f) * (to_light.y / d);
        EXPECT_NEAR(transport::direct_face_irradiance(in, top, p).r, expected, 1e-5f);
        EXPECT_EQ(transport::direct_face_irradiance(in, bottom, transport::face_point(bottom, t)),
                  glm::vec3(0.0f));
    }
}

TEST(Model, EmissivesPassThroughWallsPointLightsDoNot) {
    auto rows = open_rows();
    for (int z = 0; z < 16; ++z) rows[std::size_t(z)][8] = '#';
    scene::Scene s = transport_test::scene(rows, {8, 8}, {16, 16});
    s.point_lights.push_back({{6.5f, 8.5f}, 1.0f, {1.0f, 0.0f, 0.0f}, 1.0f, 8.0f});
    s.emissive_lights.push_back({{6.5f, 8.5f}, {0.0f, 0.0f, 1.0f}, 1.0f, 8.0f});
    const gi::FrameInputs in = inputs_of(s, 4);
    const glm::vec3 behind = transport::direct_fluence(in, {10.5f, 8.5f});
    EXPECT_EQ(behind.r, 0.0f);
    EXPECT_NEAR(behind.b, 0.5f, 1e-6f);
}

// The reference's direct term is Lantern's, texel for texel (up to Lantern's fp16 storage).
TEST(Model, DirectFluenceEqualsLanternsDirectPasses) {
    auto rows = open_rows();
    for (int i = 3; i < 12; ++i) rows[6][std::size_t(i)] = '#';
    rows[10][4] = rows[11][5] = rows[10][10] = '#';
    scene::Scene s = transport_test::scene(rows, {8, 8}, {16, 16});
    s.gi.light_softness = 1.5f;
    s.point_lights.push_back({{5.3f, 8.2f}, 1.0f, {1.0f, 0.7f, 0.4f}, 1.5f, 9.0f});
    s.point_lights.push_back(
        {{12.0f, 3.0f}, 1.0f, {0.3f, 0.5f, 1.0f}, 1.0f, 7.0f}); // on a grid corner
    s.emissive_lights.push_back({{8.5f, 5.5f}, {0.2f, 1.0f, 0.3f}, 0.8f, 4.0f});
    s.directional_lights.push_back(
        {glm::normalize(glm::vec3(0.5f, -0.6f, 0.3f)), {1.0f, 0.9f, 0.8f}, 0.7f, 4.0f, 0.5f});
    scene::ShadowProxy proxy;
    proxy.position = {7.0f, 10.0f};
    s.shadow_proxies.push_back(proxy);
    const gi::FrameInputs in = inputs_of(s, 4);
    gi::DirectTextures lantern = gi::reference_direct(in);
    gi::reference_directional(in, lantern);
    int lit = 0;
    for (int y = 0; y < in.window.height; ++y)
        for (int x = 0; x < in.window.width; ++x) {
            const glm::vec2 p = in.window.texel_center(x, y);
            if (in.walls.is_wall(int(std::floor(p.x)), int(std::floor(p.y)))) continue;
            const glm::vec3 got = transport::direct_fluence(in, p);
            const float* want = lantern.direct.at(x, y);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(got[c], want[c], 1e-3f * want[c] + 1e-6f) << x << ", " << y;
            lit += got.r > 0.0f;
        }
    EXPECT_GT(lit, 1000);
}

TEST(Model, BoundCoversTheIrradianceOfEverySegment) {
    auto rows = open_rows();
    std::mt19937 rng(7);
    for (int i = 0; i < 40; ++i) rows[rng() % 16][rng() % 16] = '#';
    scene::Scene s = transport_test::scene(rows, {8, 8}, {16, 16});
    s.gi.light_softness = 2.0f;
    s.point_lights.push_back({{7.5f, 7.5f}, 1.0f, {1.0f, 0.2f, 0.1f}, 3.0f, 10.0f});
    s.emissive_lights.push_back({{3.2f, 12.7f}, {0.1f, 0.3f, 1.0f}, 2.0f, 5.0f});
    s.directional_lights.push_back(
        {glm::normalize(glm::vec3(-0.3f, -0.5f, 0.6f)), {1.0f, 1.0f, 0.9f}, 1.0f, 4.0f, 0.5f});
    const gi::FrameInputs in = inputs_of(s, 4);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int lit = 0;
    for (int tz = 0; tz < 16; ++tz)
        for (int tx = 0; tx < 16; ++tx)
            for (int face = 0; face < 4; ++face) {
                const FaceRef f{{tx, tz}, face};
                if (!transport::face_exposed(in.walls, f)) continue;
                for (SourceKind kind :
                     {SourceKind::point, SourceKind::emissive, SourceKind::directional})
                    for (int k = 0; k < 4; ++k) {
                        const float s0 = float(k) / 4.0f, s1 = float(k + 1) / 4.0f;
                        const float bound = transport::source_face_bound(in, {kind, 0}, f, s0, s1);
                        for (int n = 0; n < 8; ++n) {
                            const float t = s0 + (s1 - s0) * unit(rng);
                            const glm::vec3 e = transport::source_face_irradiance(
                                in, {kind, 0}, f, transport::face_point(f, t));
                            EXPECT_LE(std::max(e.r, std::max(e.g, e.b)), bound * (1.0f + 1e-5f));
                            lit += e.r > 0.0f;
                        }
                    }
            }
    EXPECT_GT(lit, 200);
}

} // namespace
