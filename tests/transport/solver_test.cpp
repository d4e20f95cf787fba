// The Monte Carlo reference against known answers: unoccluded light, a sealed room, energy
// conservation, an independent quadrature of single-bounce light, honest standard errors
// and determinism across thread counts.
#include "transport_test_util.hpp"

#include "lantern/jobs/job_system.hpp"
#include "lantern/transport/model.hpp"
#include "lantern/transport/solver.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>

namespace {

using namespace lantern;
using transport::TransportResult;
using transport::TransportSettings;

TransportResult solve(const scene::Scene& s, const TransportSettings& t,
                      jobs::JobSystem* jobs = nullptr) {
    transport::SolveOptions o;
    o.jobs = jobs;
    auto r = transport::solve_transport(s, t, o);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    return std::move(r.value());
}

bool is_wall_texel(const scene::Scene& s, const gi::GiWindow& w, int x, int y) {
    const glm::vec2 p = w.texel_center(x, y);
    return s.walls.is_wall_tile(int(std::floor(p.x)), int(std::floor(p.y)));
}

// Sum over exposed faces of irradiance x segment length.
double face_power(const transport::FaceField& f) {
    double sum = 0.0;
    for (float v : f.rgb) sum += double(v);
    return sum / 3.0 / double(f.layout.resolution);
}

scene::Scene room_with_light(float radius) {
    scene::Scene s = transport_test::scene(transport_test::closed_room(), {8, 8}, {16, 16});
    s.point_lights.push_back({{7.3f, 8.4f}, 1.0f, {1.0f, 1.0f, 1.0f}, 1.0f, radius});
    return s;
}

TEST(Solver, UnoccludedLightHasExactDirectAndNoIndirect) {
    scene::Scene s =
        transport_test::scene(std::vector<std::string>(16, std::string(16, '.')), {8, 8}, {16, 16});
    s.point_lights.push_back({{8.3f, 7.6f}, 1.0f, {1.0f, 0.6f, 0.3f}, 2.0f, 6.0f});
    const TransportResult r = solve(s, transport_test::quick(0.7f));
    ASSERT_EQ(r.window.width, 64);
    for (int y = 0; y < r.window.height; ++y)
        for (int x = 0; x < r.window.width; ++x) {
            const glm::vec2 p = r.window.texel_center(x, y);
            const double d = std::hypot(double(p.x) - 8.3, double(p.y) - 7.6);
            const double f = d < 6.0 ? 2.0 * (1.0 - d / 6.0) : 0.0;
            EXPECT_NEAR(r.direct.at(x, y).r, f, 1e-5);
            EXPECT_EQ(r.indirect.at(x, y), glm::vec3(0.0f));
        }
    EXPECT_TRUE(r.stats.converged);
    EXPECT_EQ(r.stats.batches, 0); // no wall, nothing to trace
}

TEST(Solver, NoLightLeavesASealedRoom) {
    const scene::Scene s = room_with_light(12.0f); // reaches far beyond the room
    const TransportResult r = solve(s, transport_test::quick(0.8f));
    auto in_room = [](glm::vec2 p) {
        return p.x > 5.0f && p.x < 11.0f && p.y > 5.0f && p.y < 11.0f;
    };
    int lit_faces = 0;
    for (int y = 0; y < r.window.height; ++y)
        for (int x = 0; x < r.window.width; ++x) {
            const glm::vec2 p = r.window.texel_center(x, y);
            if (!is_wall_texel(s, r.window, x, y)) {
                if (in_room(p)) {
                    EXPECT_GT(r.indirect.at(x, y).r, 0.0f) << x << ", " << y;
                } else {
                    EXPECT_EQ(r.direct.at(x, y), glm::vec3(0.0f)) << x << ", " << y;
                    EXPECT_EQ(r.indirect.at(x, y), glm::vec3(0.0f)) << x << ", " << y;
                }
                continue;
            }
            for (int face = 0; face < 4; ++face) { // faces looking out of the room stay dark
                const glm::vec2 across = glm::floor(p) + 0.5f + transport::face_normal(face);
                if (in_room(across)) {
                    lit_faces += r.face_indirect.at(face, x, y).r > 0.0f;
                } else {
                    EXPECT_EQ(r.face_direct.at(face, x, y), glm::vec3(0.0f))
                        << x << ", " << y << " face " << face;
                    EXPECT_EQ(r.face_indirect.at(face, x, y), glm::vec3(0.0f))
                        << x << ", " << y << " face " << face;
                }
            }
        }
    EXPECT_GT(lit_faces, 24 * 4 * 4 / 2); // texels on the room's inner faces
}

TEST(Solver, AlbedoZeroReflectsNothing) {
    const TransportResult r = solve(room_with_light(6.0f), transport_test::quick(0.0f));
    for (float v : r.indirect.rgb) ASSERT_EQ(v, 0.0f);
    for (float v : r.face_indirect.rgb) ASSERT_EQ(v, 0.0f);
    EXPECT_GT(face_power(r.face_direct), 0.0);
    EXPECT_TRUE(r.stats.converged);
}

// Power the room's inner faces receive directly, by fine quadrature of c (1 - d/r) cos
// (nothing shadows the inside of a convex room).
double direct_power_on_room(glm::vec2 light, float radius) {
    double sum = 0.0;
    const int n = 4096;
    auto face = [&](glm::vec2 a, glm::vec2 b, glm::vec2 normal) {
        for (int i = 0; i < n; ++i) {
            const glm::vec2 p = a + (b - a) * ((float(i) + 0.5f) / float(n));
            const double d = glm::length(light - p);
            if (d >= radius) continue;
            sum += (1.0 - d / radius) * double(glm::dot(normal, (light - p))) / d *
                   double(glm::length(b - a)) / n;
        }
    };
    face({5, 5}, {11, 5}, {0, 1});
    face({5, 11}, {11, 11}, {0, -1});
    face({5, 5}, {5, 11}, {1, 0});
    face({11, 5}, {11, 11}, {-1, 0});
    return sum;
}

// In a closed room every reflected photon arrives at a wall again: the faces receive
// P (albedo + albedo^2 + ... + albedo^K) of indirect power for direct power P.
TEST(Solver, ClosedRoomConservesEnergy) {
    const double direct = direct_power_on_room({7.3f, 8.4f}, 6.0f);
    struct Case {
        float albedo;
        int bounces;
    };
    for (const Case c : {Case{0.5f, 64}, Case{1.0f, 3}}) {
        TransportSettings t = transport_test::quick(c.albedo);
        t.max_bounces = c.bounces;
        const TransportResult r = solve(room_with_light(6.0f), t);
        double expected = 0.0;
        for (int k = 1; k <= c.bounces; ++k) expected += direct * std::pow(double(c.albedo), k);
        EXPECT_NEAR(face_power(r.face_indirect), expected, 0.015 * expected)
            << "albedo " << c.albedo;
        EXPECT_NEAR(face_power(r.face_direct), direct, 0.002 * direct);
    }
}

// Single-bounce fluence in front of a lit wall, by direct quadrature over the wall:
// phi(x) = integral over the face of L(h) cos / |h - x| dh, L = albedo E(h) / 2.
double gathered_fluence(glm::vec2 x, glm::vec2 light, float radius, float albedo, float face_z,
                        float x0, float x1) {
    const int n = 20000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        const glm::vec2 h(x0 + (x1 - x0) * (float(i) + 0.5f) / float(n), face_z);
        const double dl = glm::length(light - h);
        if (dl >= radius) continue;
        const double irradiance = (1.0 - dl / radius) * double(light.y - face_z) / dl;
        const double dx = glm::length(x - h);
        sum += albedo * irradiance / 2.0 * double(x.y - face_z) / (dx * dx) * double(x1 - x0) / n;
    }
    return sum;
}

TEST(Solver, SingleBounceMatchesAnIndependentQuadrature) {
    std::vector<std::string> rows(16, std::string(16, '.'));
    for (int x = 2; x < 14; ++x) rows[4][std::size_t(x)] = '#'; // its +Z face at z = 5 is lit
    scene::Scene s = transport_test::scene(rows, {8, 8}, {16, 16});
    const glm::vec2 light(8.0f, 7.0f);
    s.point_lights.push_back({light, 1.0f, {1.0f, 1.0f, 1.0f}, 1.0f, 8.0f});
    TransportSettings t = transport_test::quick(0.6f, 1u << 16);
    t.resolution = 8;
    t.max_bounces = 1;
    const TransportResult r = solve(s, t);
    int checked = 0;
    for (int y = 0; y < r.window.height; y += 5)
        for (int x = 0; x < r.window.width; x += 7) {
            const glm::vec2 p = r.window.texel_center(x, y);
            if (p.y < 5.5f || p.y > 12.0f || p.x < 3.0f || p.x > 13.0f) continue;
            const double want = gathered_fluence(p, light, 8.0f, 0.6f, 5.0f, 2.0f, 14.0f);
            const double got = r.indirect.at(x, y).r, error = r.indirect_error.at(x, y).r;
            EXPECT_NEAR(got, want, 4.0 * error + 0.02 * want) << p.x << ", " << p.y;
            EXPECT_LT(error, 0.05 * want);
            ++checked;
        }
    EXPECT_GT(checked, 30);
}

// Two independent solves differ by what their standard errors say.
TEST(Solver, StandardErrorsAreHonest) {
    scene::Scene s = room_with_light(6.0f);
    TransportSettings t = transport_test::quick(0.5f);
    t.min_batches = t.max_batches = 16;
    const TransportResult a = solve(s, t);
    t.seed = 2;
    const TransportResult b = solve(s, t);
    double diff2 = 0.0, se2 = 0.0;
    for (std::size_t i = 0; i < a.indirect.rgb.size(); ++i) {
        const double d = double(a.indirect.rgb[i]) - double(b.indirect.rgb[i]);
        diff2 += d * d;
        se2 += double(a.indirect_error.rgb[i]) * a.indirect_error.rgb[i] +
               double(b.indirect_error.rgb[i]) * b.indirect_error.rgb[i];
    }
    ASSERT_GT(se2, 0.0);
    EXPECT_NEAR(std::sqrt(diff2 / se2), 1.0, 0.15);
}

TEST(Solver, StopsAtTheTargetError) {
    scene::Scene s = room_with_light(6.0f);
    TransportSettings t = transport_test::quick(0.5f, 1u << 12);
    t.min_batches = 4;
    t.max_batches = 1000;
    t.target_relative_error = 0.02;
    std::vector<transport::SolveProgress> seen;
    transport::SolveOptions o;
    o.progress = [&](const transport::SolveProgress& p) { seen.push_back(p); };
    auto r = transport::solve_transport(s, t, o);
    ASSERT_TRUE(r.ok());
    EXPECT_TRUE(r->stats.converged);
    EXPECT_LE(r->stats.relative_error, 0.02);
    EXPECT_LT(r->stats.batches, 1000);
    ASSERT_EQ(int(seen.size()), r->stats.batches);
    EXPECT_GT(seen[seen.size() - 2].relative_error, 0.02); // it stopped at the first batch below
    for (std::size_t i = 0; i < seen.size(); ++i) {
        EXPECT_EQ(seen[i].batch, int(i) + 1);
        EXPECT_GE(seen[i].fraction, 0.0);
        EXPECT_LE(seen[i].fraction, 1.0);
    }
    EXPECT_EQ(seen.back().fraction, 1.0);
    EXPECT_EQ(r->stats.photons, std::uint64_t(r->stats.batches) << 12);
}

TEST(Solver, SameResultForAnyThreadCount) {
    scene::Scene s = room_with_light(9.0f);
    s.emissive_lights.push_back({{9.5f, 6.5f}, {0.2f, 0.4f, 1.0f}, 1.0f, 3.0f});
    const TransportSettings t = transport_test::quick(0.6f);
    const TransportResult serial = solve(s, t);
    for (int workers : {0, 1, 3}) {
        jobs::JobSystem jobs(jobs::JobSystem::Config{workers});
        TransportResult parallel = solve(s, t, &jobs);
        EXPECT_EQ(parallel.indirect, serial.indirect) << workers << " workers";
        EXPECT_EQ(parallel.indirect_error, serial.indirect_error);
        EXPECT_EQ(parallel.face_indirect, serial.face_indirect);
        EXPECT_EQ(parallel.direct, serial.direct);
        parallel.stats.seconds = serial.stats.seconds;
        EXPECT_EQ(parallel.stats, serial.stats);
    }
}

TEST(Solver, RejectsBadSettingsAndViews) {
    const scene::Scene s = room_with_light(6.0f);
    auto fails_with = [&](TransportSettings t, const char* field) {
        auto r = transport::solve_transport(s, t);
        ASSERT_FALSE(r.ok()) << field;
        EXPECT_NE(r.error().message.find(field), std::string::npos) << r.error().message;
        EXPECT_EQ(r.error().exit_code, 2);
    };
    TransportSettings t = transport_test::quick(0.5f);
    t.albedo = 1.5f;
    fails_with(t, "transport.albedo");
    t = transport_test::quick(0.5f);
    t.photons_per_batch = 1000;
    fails_with(t, "transport.photons_per_batch");
    t = transport_test::quick(0.5f);
    t.min_batches = 1;
    fails_with(t, "transport.min_batches");
    t = transport_test::quick(0.5f);
    t.max_bounces = 0;
    fails_with(t, "transport.max_bounces");
    scene::Scene flat = s;
    flat.view =
        scene::PerspectiveCamera{{0, 10, 0}, {10, 10, 0}, 40.0f, 1.0f}; // looks at the horizon
    auto r = transport::solve_transport(flat, transport_test::quick(0.5f));
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("no GI window"), std::string::npos);
}

} // namespace

// Materials (seed 004): a white wall meeting red rock at a corner, lit by a white light,
// receives red bounce light; with white rock it receives white.
TEST(Solver, ColouredWallsTintTheirBounceLight) {
    std::vector<std::string> rows(16, std::string(16, '.'));
    for (int x = 2; x < 14; ++x) rows[4][std::size_t(x)] = '#';
    for (int z = 5; z < 13; ++z) rows[std::size_t(z)][2] = '#';
    auto white_face = [&](glm::vec3 rock) {
        scene::Scene s = transport_test::scene(rows, {8, 8}, {16, 16});
        s.materials = {{"white", {0.9f, 0.9f, 0.9f}, {}}, {"rock", rock, {}}};
        for (int x = 2; x < 14; ++x) s.walls.cells[std::size_t(4 * 16 + x)] = scene::material_cell(0);
        for (int z = 5; z < 13; ++z) s.walls.cells[std::size_t(z * 16 + 2)] = scene::material_cell(1);
        s.point_lights = {{{8.5f, 9.5f}, 1.0f, {1.0f, 1.0f, 1.0f}, 2.0f, 12.0f}};
        const TransportResult r = solve(s, transport_test::quick(0.5f, 1u << 15));
        // The +Z face of wall tiles 3 and 4 (x 3..5 on z = 5): window texels x 12..19.
        glm::dvec3 sum(0.0);
        for (int x = 12; x < 20; ++x) sum += glm::dvec3(r.face_indirect.at(gi::face_pos_z, x, 4 * 4 + 3));
        return sum;
    };
    const glm::dvec3 red = white_face({0.8f, 0.1f, 0.1f}), white = white_face({0.9f, 0.9f, 0.9f});
    EXPECT_GT(red.r, 2.0 * red.g);
    EXPECT_NEAR(red.g, red.b, 1e-9 * red.g);
    EXPECT_EQ(white.r, white.g);
    EXPECT_GT(white.g, red.g);
}

// A glowing wall in a sealed room of black walls: every photon it sends lands on another
// wall once, so the faces receive exactly its power, emission x face length.
TEST(Solver, AGlowingWallSendsItsPowerToTheOtherWalls) {
    std::vector<std::string> rows(16, std::string(16, '#'));
    for (int z = 5; z < 11; ++z) rows[std::size_t(z)].replace(5, 6, "......");
    scene::Scene s = transport_test::scene(rows, {8, 8}, {16, 16});
    s.materials = {{"lava", {0.0f, 0.0f, 0.0f}, {1.0f, 0.5f, 0.25f}}};
    for (int x = 5; x < 11; ++x) s.walls.cells[std::size_t(4 * 16 + x)] = scene::material_cell(0);
    const TransportResult r = solve(s, transport_test::quick(0.0f));
    double red = 0.0, green = 0.0;
    for (std::size_t i = 0; i < r.face_indirect.rgb.size(); i += 3) red += r.face_indirect.rgb[i], green += r.face_indirect.rgb[i + 1];
    red /= double(r.face_indirect.layout.resolution), green /= double(r.face_indirect.layout.resolution);
    EXPECT_NEAR(red, 6.0, 0.015 * 6.0) << "six faces of emission 1";
    EXPECT_NEAR(green / red, 0.5, 1e-9);
    EXPECT_EQ(face_power(r.face_direct), 0.0);
}
