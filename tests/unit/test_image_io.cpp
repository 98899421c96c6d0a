// Texture images: every format and variant read with exact pixel values (top-left origin),
// PNG round trips, and damaged or lying files refused with an IoError that names the file,
// the line (text formats) and the reason.
#include <stb/stb_image_write.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <random>
#include <set>

#include "core/errors.h"
#include "core/io/file_util.h"
#include "core/io/image_io.h"
#include "test_helpers.h"

using namespace trilab;
using namespace trilab::test;
using Catch::Matchers::Contains;

namespace {

using Rgba = std::array<int, 4>;
using Pixels = std::vector<Rgba>;  // row-major, top row first

void write_bytes(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

Rgba pixel(const Image& image, int x, int y) {
    const std::uint8_t* p = image.rgba.data() + 4 * (std::size_t(y) * image.width + x);
    return {p[0], p[1], p[2], p[3]};
}

void require_pixels(const Image& image, int width, int height, const Pixels& expected) {
    REQUIRE(image.width == width);
    REQUIRE(image.height == height);
    REQUIRE(image.rgba.size() == std::size_t(width) * height * 4);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            INFO("pixel (" << x << ", " << y << ")");
            REQUIRE(pixel(image, x, y) == expected[std::size_t(y) * width + x]);
        }
}

Pixels grey(const std::vector<int>& values) {
    Pixels p;
    for (int v : values) p.push_back({v, v, v, 255});
    return p;
}

/// 1 is black, 0 white.
Pixels bits(const std::vector<int>& values) {
    Pixels p;
    for (int b : values) p.push_back(b ? Rgba{0, 0, 0, 255} : Rgba{255, 255, 255, 255});
    return p;
}

// The 4x3 fixture in tests/data/images (see the files; the same values in every format).
const Pixels kRgb = {{255, 0, 0, 255},     {0, 255, 0, 255},    {0, 0, 255, 255},
                     {255, 255, 255, 255}, {0, 0, 0, 255},      {128, 128, 128, 255},
                     {255, 255, 0, 255},   {0, 255, 255, 255},  {255, 0, 255, 255},
                     {10, 20, 30, 255},    {200, 100, 50, 255}, {1, 2, 3, 255}};
const Pixels kRgba = {{255, 0, 0, 255},     {0, 255, 0, 255},    {0, 0, 255, 255},
                      {255, 255, 255, 255}, {0, 0, 0, 255},      {128, 128, 128, 255},
                      {255, 255, 0, 255},   {0, 255, 255, 255},  {255, 0, 255, 255},
                      {10, 20, 30, 64},     {200, 100, 50, 255}, {1, 2, 3, 0}};
const std::vector<int> kBits = {1, 0, 0, 1, 0, 1, 1, 0, 1, 1, 0, 1};

std::string image_file(const std::string& name) {
    return data_file("images/" + name);
}

std::string bad_file(const std::string& name) {
    return data_file("bad/" + name);
}

/// The IoError message of read_image(path), "" when it loads.
std::string image_error(const std::string& path) {
    try {
        read_image(path);
    } catch (const IoError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("read_image reads the 4x3 fixture in every format with exact pixels", "[image]") {
    struct Case {
        const char* file;
        Pixels expected;
    };
    const Rgba none = {0, 0, 0, 0};
    const std::vector<Case> cases = {
        {"rgba_4x3.png", kRgba},
        {"rgb_4x3.bmp", kRgb},            // 24 bit, bottom-up rows
        {"rgba_topdown_4x3.bmp", kRgba},  // 32 bit with alpha, negative height
        {"rgb_p3.ppm", kRgb},             // ASCII, comment
        {"rgb_p6.ppm", kRgb},             // binary, comment
        {"rgb_p6.pnm", kRgb},             // header on one line, .pnm extension
        {"gray_p2.pgm", grey({0, 17, 34, 51, 68, 85, 102, 119, 136, 153, 170, 255})},  // max 15
        {"gray_p5.pgm", grey({0, 50, 100, 150, 200, 250, 255, 1, 2, 3, 4, 5})},
        {"gray16_p5.pgm", grey({0, 255, 128, 4, 1, 2, 254, 48, 156, 0, 0, 255})},  // 16 bit
        {"bits_p1.pbm", bits(kBits)},  // bits with and without spaces
        {"bits_p4.pbm", bits(kBits)},
        {"bits_4x3.xbm", bits(kBits)},  // with hot spot
        // 2 characters per pixel, None, #RGB, #RRRRGGGGBBBB, names, m and s keys.
        {"rgba_4x3.xpm",
         {{255, 0, 0, 255},
          {0, 255, 0, 255},
          {0, 0, 255, 255},
          {255, 255, 255, 255},
          {0, 0, 0, 255},
          none,
          {255, 165, 0, 255},
          {211, 211, 211, 255},
          none,
          {255, 0, 0, 255},
          none,
          {0, 0, 0, 255}}},
    };
    for (const Case& c : cases) {
        INFO(c.file);
        require_pixels(read_image(image_file(c.file)), 4, 3, c.expected);
    }
}

TEST_CASE("read_image reads PNG and BMP files that stb_image_write produced", "[image]") {
    TempDir dir;
    // 5 x 2: BMP rows of 15 bytes are padded to 16.
    const int w = 5, h = 2;
    std::vector<std::uint8_t> rgba(w * h * 4);
    for (std::size_t i = 0; i < rgba.size(); ++i) rgba[i] = std::uint8_t(i * 37 + 11);
    for (int comp = 1; comp <= 4; ++comp) {
        INFO("components " << comp);
        // Keep `comp` channels of each pixel.
        std::vector<std::uint8_t> data;
        for (int p = 0; p < w * h; ++p)
            for (int k = 0; k < comp; ++k) data.push_back(rgba[std::size_t(p) * 4 + k]);
        Pixels expected;
        for (int p = 0; p < w * h; ++p) {
            const std::uint8_t* s = data.data() + std::size_t(p) * comp;
            if (comp <= 2)
                expected.push_back({s[0], s[0], s[0], comp == 2 ? s[1] : 255});
            else
                expected.push_back({s[0], s[1], s[2], comp == 4 ? s[3] : 255});
        }
        stbi_flip_vertically_on_write(0);
        const std::string png = dir.path("w" + std::to_string(comp) + ".png");
        REQUIRE(stbi_write_png(png.c_str(), w, h, comp, data.data(), w * comp));
        require_pixels(read_image(png), w, h, expected);
        if (comp == 3) {
            const std::string bmp = dir.path("w.bmp");
            REQUIRE(stbi_write_bmp(bmp.c_str(), w, h, comp, data.data()));
            require_pixels(read_image(bmp), w, h, expected);
        }
    }
}

TEST_CASE("read_image reads every PNM variant", "[image]") {
    TempDir dir;
    SECTION("P1 and P4 with rows padded to whole bytes") {
        // 10 x 2: P4 rows take two bytes, MSB first.
        const std::vector<int> b = {1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 0, 1, 0, 0, 1, 1, 1, 0, 0, 1};
        std::string p1 = "P1\n# comment\n10 2\n";
        for (std::size_t i = 0; i < b.size(); ++i)
            p1 += (b[i] ? "1" : "0") + std::string(i % 3 ? "" : " ");
        p1 += "\n";
        write_bytes(dir.path("a.pbm"), p1);
        require_pixels(read_image(dir.path("a.pbm")), 10, 2, bits(b));
        std::string p4 = "P4 10 2\n";
        p4 += char(0xb1);  // 1011 0001
        p4 += char(0x80);  // 10 (padding)
        p4 += char(0x4e);  // 0100 1110
        p4 += char(0x40);  // 01
        write_bytes(dir.path("b.pbm"), p4);
        require_pixels(read_image(dir.path("b.pbm")), 10, 2, bits(b));
    }
    SECTION("P2 and P3 with maxval scaling, comments and CRLF") {
        write_bytes(dir.path("a.pgm"), "P2\r\n# c\r\n3 1\r\n1000\r\n0 500 1000 # end\r\n");
        require_pixels(read_image(dir.path("a.pgm")), 3, 1, grey({0, 128, 255}));
        write_bytes(dir.path("a.ppm"), "P3 2 1 1 0 1 0\n1 0 1\n");
        require_pixels(read_image(dir.path("a.ppm")), 2, 1, {{0, 255, 0, 255}, {255, 0, 255, 255}});
    }
    SECTION("P6 with 16-bit samples") {
        std::string p6 = "P6\n1 1\n65535\n";
        for (int v : {0xffff, 0x0000, 0x8080}) {
            p6 += char(v >> 8);
            p6 += char(v & 0xff);
        }
        write_bytes(dir.path("a.ppm"), p6);
        require_pixels(read_image(dir.path("a.ppm")), 1, 1, {{255, 0, 128, 255}});
    }
}

TEST_CASE("read_image reads XBM variants", "[image]") {
    TempDir dir;
    // 10 x 2: two bytes per row, LSB first.
    const std::vector<int> b = {1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 0, 1, 0, 0, 1, 1, 1, 0, 0, 1};
    SECTION("X11 bytes, comments, decimal and trailing comma") {
        write_bytes(dir.path("a.xbm"),
                    "/* made by hand */\n#define a_width 10\n#define a_height 2\n"
                    "static const unsigned char a_bits[4] = {\n"
                    "  0x8d, 0x01, // row 0\n  0x72, 0x02, };\n");
        require_pixels(read_image(dir.path("a.xbm")), 10, 2, bits(b));
    }
    SECTION("X10 16-bit words") {
        write_bytes(dir.path("a.xbm"),
                    "#define a_width 10\n#define a_height 2\n"
                    "static short a_bits[] = { 0x018d, 0x0272 };\n");
        require_pixels(read_image(dir.path("a.xbm")), 10, 2, bits(b));
    }
}

TEST_CASE("read_image reads XPM variants", "[image]") {
    TempDir dir;
    SECTION("one character per pixel, colour spellings, hot spot and extensions") {
        write_bytes(dir.path("a.xpm"),
                    "/* XPM */\n"
                    "static const char *const a_xpm[] = {\n"
                    "/* values */ \"6 2 6 1 0 0 XPMEXT\",\n"
                    "\". c None s mask\",\n"
                    "\"# c #fff\",\n"  // #RGB scales: #fff is white
                    "\"a c #808080\",\n"
                    "\"b g4 Gray50\",\n"  // no c key: g4 is used
                    "\"c c Light Grey\",\n"
                    "\"d c #123456789abc\",\n"
                    "\".#abcd\",\n"
                    "\"dcba#.\" \n,\n"
                    "\"XPMEXT ext1 data\",\n\"XPMENDEXT\"\n};\n");
        const Rgba none = {0, 0, 0, 0}, white = {255, 255, 255, 255};
        const Rgba a = {128, 128, 128, 255}, g50 = {127, 127, 127, 255};
        const Rgba lg = {211, 211, 211, 255}, d = {0x12, 0x56, 0x9a, 255};
        require_pixels(read_image(dir.path("a.xpm")), 6, 2,
                       {none, white, a, g50, lg, d, d, lg, g50, a, white, none});
    }
    SECTION("three characters per pixel with spaces and adjacent strings") {
        write_bytes(dir.path("b.xpm"),
                    "/* XPM */\nstatic char* b[] = {\n\"2 1 2 3\",\n"
                    "\" x  c blue\",\n\"x x c yellow\",\n\" x \" \"x x\"};");
        require_pixels(read_image(dir.path("b.xpm")), 2, 1, {{0, 0, 255, 255}, {255, 255, 0, 255}});
    }
    SECTION("the basic X11 colour names") {
        const std::vector<std::pair<std::string, Rgba>> names = {
            {"black", {0, 0, 0, 255}},      {"white", {255, 255, 255, 255}},
            {"red", {255, 0, 0, 255}},      {"green", {0, 255, 0, 255}},
            {"blue", {0, 0, 255, 255}},     {"yellow", {255, 255, 0, 255}},
            {"cyan", {0, 255, 255, 255}},   {"magenta", {255, 0, 255, 255}},
            {"gray", {190, 190, 190, 255}}, {"grey", {190, 190, 190, 255}},
            {"orange", {255, 165, 0, 255}}, {"NONE", {0, 0, 0, 0}}};
        for (const auto& [name, rgba] : names) {
            INFO(name);
            write_bytes(dir.path("c.xpm"), "/* XPM */\nstatic char* c[] = {\"1 1 1 1\", \"x c " +
                                               name + "\", \"x\"};\n");
            require_pixels(read_image(dir.path("c.xpm")), 1, 1, {rgba});
        }
    }
}

TEST_CASE("write_png and read_image round-trip exactly", "[image]") {
    TempDir dir;
    Image random;
    random.width = 37;
    random.height = 23;
    std::mt19937 rng(7);
    for (int i = 0; i < random.width * random.height * 4; ++i)
        random.rgba.push_back(std::uint8_t(rng()));
    for (const Image& image : {random, make_checkerboard(64, 4), make_checkerboard(7, 3)}) {
        write_png(image, dir.path("r.png"));
        const Image back = read_image(dir.path("r.png"));
        REQUIRE(back.width == image.width);
        REQUIRE(back.height == image.height);
        REQUIRE(back.rgba == image.rgba);
    }
    // Rows stay top to bottom even after someone turned stb's global flip on.
    stbi_flip_vertically_on_write(1);
    write_png(random, dir.path("f.png"));
    REQUIRE(read_image(dir.path("f.png")).rgba == random.rgba);
    // Only the final file remains (no temporaries).
    std::size_t files = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir.dir()))
        files += e.is_regular_file();
    REQUIRE(files == 2);
}

TEST_CASE("write_png refuses bad images and unwritable paths with IoError", "[image]") {
    TempDir dir;
    REQUIRE_THROWS_AS(write_png(Image{}, dir.path("e.png")), IoError);
    Image wrong;
    wrong.width = 2;
    wrong.height = 2;
    wrong.rgba.resize(15);
    REQUIRE_THROWS_WITH(write_png(wrong, dir.path("w.png")), Contains("w.png") && Contains("16"));
    REQUIRE_THROWS_WITH(write_png(make_checkerboard(8, 2), dir.path("missing/x.png")),
                        Contains("missing/x.png"));
    REQUIRE_FALSE(exists(dir.path("e.png")));
    REQUIRE_FALSE(exists(dir.path("w.png")));
}

TEST_CASE("make_checkerboard alternates two opaque greys", "[image]") {
    const Image c = make_checkerboard(64, 8);
    REQUIRE(c.width == 64);
    REQUIRE(c.height == 64);
    REQUIRE(c.rgba.size() == 64 * 64 * 4);
    const Rgba light = pixel(c, 0, 0), dark = pixel(c, 8, 0);
    REQUIRE(light[0] > dark[0]);
    for (const Rgba& p : {light, dark}) {
        REQUIRE(p[0] == p[1]);
        REQUIRE(p[1] == p[2]);
        REQUIRE(p[3] == 255);
    }
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            REQUIRE(pixel(c, x, y) == (((x / 8) + (y / 8)) % 2 == 0 ? light : dark));
    REQUIRE(make_checkerboard().width == 512);
    REQUIRE_THROWS_AS(make_checkerboard(0, 1), InvalidArgument);
    REQUIRE_THROWS_AS(make_checkerboard(16, 0), InvalidArgument);
    REQUIRE_THROWS_AS(make_checkerboard(4, 8), InvalidArgument);
}

TEST_CASE("read_image chooses the format by extension", "[image]") {
    const auto exts = supported_image_extensions();
    for (const char* e : {"bmp", "png", "pnm", "ppm", "pgm", "pbm", "xbm", "xpm"})
        REQUIRE(std::find(exts.begin(), exts.end(), e) != exts.end());
    TempDir dir;
    std::filesystem::copy_file(image_file("rgba_4x3.png"), dir.path("UPPER.PNG"));
    require_pixels(read_image(dir.path("UPPER.PNG")), 4, 3, kRgba);
    // A PNG named .bmp is refused by the BMP reader.
    std::filesystem::copy_file(image_file("rgba_4x3.png"), dir.path("png.bmp"));
    REQUIRE_THROWS_WITH(read_image(dir.path("png.bmp")), Contains("png.bmp") && Contains("BM"));
    REQUIRE_THROWS_WITH(read_image(dir.path("noext")), Contains("no extension"));
    REQUIRE_THROWS_WITH(read_image(dir.path("missing.png")), Contains("missing.png"));
}

TEST_CASE("bad image files give an IoError naming the file, the line and the reason",
          "[image][bad]") {
    struct Case {
        const char* file;
        std::size_t line;
        const char* reason;
    };
    const Case cases[] = {
        {"img_truncated.png", 0, "PNG"},
        {"img_not_png.png", 0, "not a PNG file"},
        {"img_empty.png", 0, "empty"},
        {"img_huge.png", 0, "limit"},
        {"img_truncated.bmp", 0, "truncated"},
        {"img_huge.bmp", 0, "limit"},
        {"img_p6_huge.ppm", 2, "limit of 32768 pixels per side"},
        {"img_p6_truncated.ppm", 0, "truncated"},
        {"img_p3_bad_sample.ppm", 5, "sample 256 is outside 0 to 255"},
        {"img_p3_too_many.ppm", 5, "more values"},
        {"img_p2_truncated.pgm", 5, "unexpected end of file"},
        {"img_p1_bad_bit.pbm", 4, "not a sequence of bits"},
        {"img_pnm_bad_magic.pnm", 1, "not a PNM file"},
        {"img_p5_bad_maxval.pgm", 3, "maximum value 70000"},
        {"img_xbm_missing_height.xbm", 2, "_height"},
        {"img_xbm_count.xbm", 4, "found 2 values"},
        {"img_xbm_bad_value.xbm", 5, "not a byte value"},
        {"img_xbm_huge.xbm", 2, "limit"},
        {"img_xbm_garbage.xbm", 3, "'@'"},
        {"img_xpm_unknown_colour.xpm", 5, "unknown colour 'notacolour'"},
        {"img_xpm_unknown_code.xpm", 6, "unknown pixel code 'z' in column 2"},
        {"img_xpm_short_row.xpm", 6, "2 characters, expected 3"},
        {"img_xpm_missing_rows.xpm", 6, "only 3 strings"},
        {"img_xpm_no_marker.xpm", 1, "not an XPM file"},
        {"img_xpm_huge.xpm", 3, "limit"},
        {"img_xpm_unterminated.xpm", 4, "unterminated string"},
        {"img_xpm_bad_hex.xpm", 4, "unknown colour '#12345'"},
        {"img_unsupported.tga", 0, "unsupported image extension '.tga'"},
    };
    for (const Case& c : cases) {
        const std::string path = bad_file(c.file);
        INFO(c.file);
        try {
            read_image(path);
            FAIL("no IoError");
        } catch (const IoError& e) {
            INFO(e.what());
            REQUIRE(e.file() == path);
            REQUIRE(e.line() == c.line);
            REQUIRE_THAT(e.reason(), Contains(c.reason));
            REQUIRE_THAT(std::string(e.what()), Contains(c.file));
        }
    }
}

TEST_CASE("every img_ file in tests/data/bad throws IoError", "[image][bad]") {
    std::size_t n = 0;
    for (const auto& entry : std::filesystem::directory_iterator(data_file("bad"))) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("img_", 0) != 0) continue;
        INFO(name);
        REQUIRE_THROWS_WITH(read_image(entry.path().string()), Contains(name));
        ++n;
    }
    REQUIRE(n >= 25);
}

TEST_CASE("absurd image dimensions are refused quickly, before allocating", "[image][bad]") {
    TempDir dir;
    struct Case {
        const char* name;
        std::string bytes;
        const char* reason;
    };
    const std::vector<Case> cases = {
        {"side.ppm", "P6 40000 10 255\n", "per side"},
        {"pixels.pgm", "P5 20000 20000 255\n", "268435456 pixels"},
        {"negative.pbm", "P4 -5 10\n", "must be positive"},
        {"zero.ppm", "P3 0 10 255\n", "must be positive"},
        {"overflow.pgm", "P2 99999999999999999999 1 255\n", "not an integer"},
        // Within the limits, but the file cannot hold the pixels: refused before allocating.
        {"lying_binary.ppm", "P6 30000 8000 255\n" + std::string(100, 'x'), "truncated"},
        {"lying_ascii.ppm", "P3 30000 8000 255\n1 2 3\n", "more than the file's"},
        {"lying.xbm",
         "#define a_width 30000\n#define a_height 8000\nstatic char a_bits[] = { 1 };\n",
         "more than the file's"},
        {"lying.xpm", "/* XPM */\nstatic char*a[]={\"30000 8000 1 1\",\"a c red\",\"a\"};\n",
         "only 2 strings"},
        {"huge.xpm", "/* XPM */\nstatic char*a[]={\"5 5 99999999999 1\",\"a c red\",\"a\"};\n",
         "only 2 strings"},
    };
    const auto start = std::chrono::steady_clock::now();
    for (const Case& c : cases) {
        INFO(c.name);
        write_bytes(dir.path(c.name), c.bytes);
        const std::string msg = image_error(dir.path(c.name));
        REQUIRE_THAT(msg, Contains(c.name) && Contains(c.reason));
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    REQUIRE(seconds < 2.0);
}

TEST_CASE("damaged images load with consistent sizes or throw IoError", "[image][robustness]") {
    TempDir dir;
    std::mt19937 rng(20261122);
    int rounds = 120;
    if (const char* env = std::getenv("TRILAB_FUZZ_ROUNDS")) rounds = std::max(1, std::atoi(env));
    std::set<std::string> formats_that_loaded;
    for (const auto& entry : std::filesystem::directory_iterator(data_file("images"))) {
        const std::string name = entry.path().filename().string();
        const std::string original = read_file_bytes(entry.path().string());
        const std::string damaged = dir.path("damaged_" + name);
        for (int round = 0; round < rounds; ++round) {
            std::string bytes = original;
            const int kind = int(rng() % 4);
            if (kind == 0) {
                for (int k = 0, n = 1 + int(rng() % 4); k < n; ++k)
                    bytes[rng() % bytes.size()] = char(rng());
            } else if (kind == 1) {
                bytes.resize(rng() % bytes.size());
            } else if (kind == 2) {
                bytes.insert(rng() % bytes.size(), std::string(1 + rng() % 16, char(rng())));
            } else {
                std::string garbage = bytes.substr(0, std::min<std::size_t>(bytes.size(), 12));
                for (int k = 0, n = int(rng() % 2048); k < n; ++k) garbage += char(rng());
                bytes = garbage;
            }
            write_bytes(damaged, bytes);
            INFO(name << " round " << round << " kind " << kind);
            try {
                const Image image = read_image(damaged);
                REQUIRE(image.width > 0);
                REQUIRE(image.height > 0);
                REQUIRE(image.rgba.size() == std::size_t(image.width) * image.height * 4);
                formats_that_loaded.insert(name);
            } catch (const IoError& e) {
                REQUIRE_THAT(std::string(e.what()), Contains(damaged));
            }
        }
    }
    REQUIRE(!formats_that_loaded.empty());
}
