// The XWD parser: golden dumps built here (both byte orders, 16/24/32 bits per pixel, row
// padding, a window name and a colour map to skip), every truncated length, unsupported
// kinds; and a real capture of a window under Xvfb.
#include "platform/xvfb_support.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

namespace lantern::test {
namespace {

struct XwdSpec {
    std::uint32_t width = 3, height = 2;
    std::uint32_t bits_per_pixel = 32;
    std::uint32_t bytes_per_line = 12;
    std::uint32_t byte_order = 0; // 0 LSBFirst, 1 MSBFirst
    std::uint32_t red_mask = 0xff0000, green_mask = 0xff00, blue_mask = 0xff;
    std::uint32_t visual_class = 4;  // TrueColor
    std::uint32_t pixmap_format = 2; // ZPixmap
    std::uint32_t ncolors = 2;
    std::string name = "window";
};

void put_be32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8)
        out.push_back(static_cast<std::uint8_t>(v >> shift));
}

// An XWD file as xwd writes it: header, name, colour map, then rows of `pixels` (raw
// values) in the spec's byte order, padded to bytes_per_line.
std::vector<std::uint8_t> make_xwd(const XwdSpec& s, const std::vector<std::uint32_t>& pixels) {
    std::vector<std::uint8_t> out;
    const std::uint32_t header_size = 100 + static_cast<std::uint32_t>(s.name.size()) + 1;
    const std::array<std::uint32_t, 25> header = {header_size,
                                                  7,
                                                  s.pixmap_format,
                                                  24,
                                                  s.width,
                                                  s.height,
                                                  0,
                                                  s.byte_order,
                                                  32,
                                                  s.byte_order,
                                                  32,
                                                  s.bits_per_pixel,
                                                  s.bytes_per_line,
                                                  s.visual_class,
                                                  s.red_mask,
                                                  s.green_mask,
                                                  s.blue_mask,
                                                  8,
                                                  256,
                                                  s.ncolors,
                                                  s.width,
                                                  s.height,
                                                  0,
                                                  0,
                                                  0};
    for (std::uint32_t word : header) put_be32(out, word);
    out.insert(out.end(), s.name.begin(), s.name.end());
    out.push_back(0);
    for (std::uint32_t i = 0; i < s.ncolors * 12; ++i) out.push_back(static_cast<std::uint8_t>(i));
    const std::uint32_t pixel_bytes = s.bits_per_pixel / 8;
    for (std::uint32_t y = 0; y < s.height; ++y) {
        for (std::uint32_t x = 0; x < s.width; ++x) {
            const std::uint32_t v = pixels[y * s.width + x];
            for (std::uint32_t b = 0; b < pixel_bytes; ++b) {
                const std::uint32_t byte = s.byte_order == 0 ? b : pixel_bytes - 1 - b;
                out.push_back(static_cast<std::uint8_t>(v >> (8 * byte)));
            }
        }
        for (std::uint32_t pad = s.width * pixel_bytes; pad < s.bytes_per_line; ++pad)
            out.push_back(0xee);
    }
    return out;
}

const std::vector<std::uint32_t> six_pixels = {0xff0000, 0x00ff00, 0x0000ff,
                                               0x123456, 0xffffff, 0x000000};

void expect_six_pixels(const RgbImage& image) {
    ASSERT_EQ(image.width, 3u);
    ASSERT_EQ(image.height, 2u);
    for (std::uint32_t i = 0; i < 6; ++i)
        EXPECT_EQ(image.at(i % 3, i / 3), six_pixels[i]) << "pixel " << i;
}

TEST(Xwd, ParsesLsbFirst32Bit) {
    auto image = parse_xwd(make_xwd({}, six_pixels));
    ASSERT_TRUE(image) << image.error().message;
    expect_six_pixels(*image);
}

TEST(Xwd, ParsesMsbFirst24BitWithRowPadding) {
    XwdSpec spec;
    spec.bits_per_pixel = 24;
    spec.bytes_per_line = 12; // 9 bytes of pixels + 3 of padding
    spec.byte_order = 1;
    auto image = parse_xwd(make_xwd(spec, six_pixels));
    ASSERT_TRUE(image) << image.error().message;
    expect_six_pixels(*image);
}

TEST(Xwd, Scales16BitChannelsToEightBits) {
    XwdSpec spec; // RGB 565
    spec.width = 2;
    spec.height = 1;
    spec.bits_per_pixel = 16;
    spec.bytes_per_line = 4;
    spec.red_mask = 0xf800;
    spec.green_mask = 0x07e0;
    spec.blue_mask = 0x001f;
    auto image = parse_xwd(make_xwd(spec, {0xf800 | 0x001f, 0x0400 | 0x0010}));
    ASSERT_TRUE(image) << image.error().message;
    EXPECT_EQ(image->at(0, 0), 0xff00ffu);
    EXPECT_EQ(image->at(1, 0), 0x008284u); // 32/63 and 16/31 of full scale, rounded
}

TEST(Xwd, EveryTruncatedLengthIsAnError) {
    const std::vector<std::uint8_t> file = make_xwd({}, six_pixels);
    for (std::size_t length = 0; length < file.size(); ++length) {
        auto image = parse_xwd(std::span(file.data(), length));
        EXPECT_FALSE(image) << "length " << length;
    }
}

TEST(Xwd, UnsupportedKindsAreErrors) {
    XwdSpec pseudo;
    pseudo.visual_class = 3; // PseudoColor
    auto a = parse_xwd(make_xwd(pseudo, six_pixels));
    ASSERT_FALSE(a);
    EXPECT_NE(a.error().message.find("TrueColor"), std::string::npos);
    XwdSpec xy;
    xy.pixmap_format = 1; // XYPixmap
    auto b = parse_xwd(make_xwd(xy, six_pixels));
    ASSERT_FALSE(b);
    EXPECT_NE(b.error().message.find("ZPixmap"), std::string::npos);
    XwdSpec short_rows;
    short_rows.bytes_per_line = 8; // shorter than 3 pixels of 4 bytes
    EXPECT_FALSE(parse_xwd(make_xwd(short_rows, six_pixels)));
}

TEST(Xwd, CapturesAWindowOfXvfb) {
    LANTERN_REQUIRE_XVFB();
    // The root window: Xvfb's screen, always there, 1280x720 as the harness starts it.
    auto dump = run_tool({"xwd", "-root", "-silent"});
    ASSERT_TRUE(dump) << dump.error().message;
    auto image = parse_xwd({reinterpret_cast<const std::uint8_t*>(dump->data()), dump->size()});
    ASSERT_TRUE(image) << image.error().message;
    EXPECT_EQ(image->width, 1280u);
    EXPECT_EQ(image->height, 720u);
}

} // namespace
} // namespace lantern::test
