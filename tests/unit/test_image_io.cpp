// Texture images: every format and variant read with exact pixel values (top-left origin),
// PNG round trips, and damaged or lying files refused with an IoError that names the file,
// the line (text formats) and the reason.
#include <stb/stb_image_write.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <random>
#include <set>
#include <sstream>

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
    return error_text<IoError>([&] { read_image(path); });
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
        {"pixels.pgm", "P5 20000 20000 255\n", "(400000000 pixels) exceeds the limit of 67108864"},
        {"negative.pbm", "P4 -5 10\n", "must be positive"},
        {"zero.ppm", "P3 0 10 255\n", "must be positive"},
        {"overflow.pgm", "P2 99999999999999999999 1 255\n", "not an integer"},
        // Within the limits, but the file cannot hold the pixels: refused before allocating.
        {"lying_binary.ppm", "P6 8000 8000 255\n" + std::string(100, 'x'), "truncated"},
        {"lying_ascii.ppm", "P3 8000 8000 255\n1 2 3\n", "more than the file's"},
        {"lying.xbm",
         "#define a_width 8000\n#define a_height 8000\nstatic char a_bits[] = { 1 };\n",
         "more than the file's"},
        {"lying.xpm", "/* XPM */\nstatic char*a[]={\"8000 8000 1 1\",\"a c red\",\"a\"};\n",
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

// ---- hand-made PNG: the bounded inflate, the pixel budget ---------------------------------

namespace {

std::string be32(std::uint32_t v) {
    return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

std::string png_chunk(const std::string& type, const std::string& data) {
    const std::string body = type + data;
    const auto crc = crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()));
    return be32(std::uint32_t(data.size())) + body + be32(std::uint32_t(crc));
}

std::string zlib_compress(const std::string& raw) {
    uLongf size = compressBound(uLong(raw.size()));
    std::string out(size, '\0');
    REQUIRE(compress2(reinterpret_cast<Bytef*>(&out[0]), &size,
                      reinterpret_cast<const Bytef*>(raw.data()), uLong(raw.size()), 9) == Z_OK);
    out.resize(size);
    return out;
}

/// A PNG around the given zlib stream, its IDAT data cut into chunks of `chunk` bytes.
std::string png_file(std::uint32_t width, std::uint32_t height, int depth, int colour_type,
                     const std::string& zdata, bool interlaced = false, std::size_t chunk = 0,
                     const std::string& plte = "") {
    std::string ihdr = be32(width) + be32(height);
    ihdr += char(depth);
    ihdr += char(colour_type);
    ihdr += std::string(2, '\0');  // compression, filter method
    ihdr += char(interlaced ? 1 : 0);
    std::string out = "\x89PNG\r\n\x1a\n" + png_chunk("IHDR", ihdr);
    if (!plte.empty()) out += png_chunk("PLTE", plte);
    if (chunk == 0) chunk = std::max<std::size_t>(1, zdata.size());
    for (std::size_t at = 0; at < zdata.size(); at += chunk)
        out += png_chunk("IDAT", zdata.substr(at, chunk));
    return out + png_chunk("IEND", "");
}

/// The filtered scanlines (filter 0 everywhere) of `samples` (row-major, `channels` per
/// pixel, `depth` bits each, packed most significant bit first, 16 bit big-endian), in one
/// pass or the seven Adam7 passes, written from the PNG specification.
std::string scanlines(std::uint32_t width, std::uint32_t height, int channels, int depth,
                      const std::vector<unsigned>& samples, bool interlaced) {
    struct Pass {
        std::uint32_t x0, y0, dx, dy;
    };
    const std::vector<Pass> passes =
        interlaced ? std::vector<Pass>{{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4},
                                       {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}}
                   : std::vector<Pass>{{0, 0, 1, 1}};
    std::string out;
    for (const Pass& p : passes) {
        if (p.x0 >= width || p.y0 >= height) continue;
        for (std::uint32_t y = p.y0; y < height; y += p.dy) {
            out += '\0';
            unsigned acc = 0, bits = 0;
            for (std::uint32_t x = p.x0; x < width; x += p.dx)
                for (int c = 0; c < channels; ++c) {
                    const unsigned v = samples[(std::size_t(y) * width + x) * channels + c];
                    if (depth == 16) {
                        out += char(v >> 8);
                        out += char(v);
                    } else if (depth == 8) {
                        out += char(v);
                    } else {
                        acc = acc << depth | v;
                        bits += unsigned(depth);
                        if (bits == 8) {
                            out += char(acc);
                            acc = bits = 0;
                        }
                    }
                }
            if (bits > 0) out += char(acc << (8 - bits));  // pad the row's last byte
        }
    }
    return out;
}

}  // namespace

TEST_CASE("PNG files pass the bounded inflate with exact pixels", "[image]") {
    TempDir dir;
    SECTION("RGB, the image data cut into chunks of 3 bytes") {
        const std::vector<unsigned> s = {255, 0,  0,  0,  255, 0,  0,  0,  255,
                                         10,  20, 30, 40, 50,  60, 70, 80, 90};
        write_bytes(dir.path("rgb.png"),
                    png_file(3, 2, 8, 2, zlib_compress(scanlines(3, 2, 3, 8, s, false)), false, 3));
        require_pixels(read_image(dir.path("rgb.png")), 3, 2,
                       {{255, 0, 0, 255},
                        {0, 255, 0, 255},
                        {0, 0, 255, 255},
                        {10, 20, 30, 255},
                        {40, 50, 60, 255},
                        {70, 80, 90, 255}});
    }
    SECTION("interlaced (Adam7) grey, 8 and 1 bits") {
        for (int depth : {8, 1}) {
            INFO(depth << " bits");
            const std::uint32_t w = 9, h = 5;
            std::vector<unsigned> s;
            Pixels expected;
            for (std::uint32_t i = 0; i < w * h; ++i) {
                const unsigned v = depth == 8 ? (i * 37) % 256 : (i * 7 / 3) % 2;
                s.push_back(v);
                const int g = depth == 8 ? int(v) : int(v) * 255;
                expected.push_back({g, g, g, 255});
            }
            write_bytes(
                dir.path("adam7.png"),
                png_file(w, h, depth, 0, zlib_compress(scanlines(w, h, 1, depth, s, true)), true));
            require_pixels(read_image(dir.path("adam7.png")), int(w), int(h), expected);
        }
    }
    SECTION("grey and alpha, 16 bits (read as the high bytes)") {
        const std::vector<unsigned> s = {0x1234, 0xffff, 0xab00, 0x0001, 0x8080, 0x7fff, 0, 0x0100};
        write_bytes(dir.path("ga16.png"),
                    png_file(2, 2, 16, 4, zlib_compress(scanlines(2, 2, 2, 16, s, false))));
        require_pixels(read_image(dir.path("ga16.png")), 2, 2,
                       {{0x12, 0x12, 0x12, 255},
                        {0xab, 0xab, 0xab, 0},
                        {0x80, 0x80, 0x80, 0x7f},
                        {0, 0, 0, 1}});
    }
    SECTION("a 2-bit palette, interlaced") {
        const std::string plte = std::string("\xff\x00\x00", 3) + std::string("\x00\xff\x00", 3) +
                                 std::string("\x00\x00\xff", 3) + std::string("\x10\x20\x30", 3);
        const std::vector<unsigned> s = {0, 1, 2, 3, 3, 2, 1, 0, 1, 1};
        write_bytes(
            dir.path("pal.png"),
            png_file(5, 2, 2, 3, zlib_compress(scanlines(5, 2, 1, 2, s, true)), true, 0, plte));
        const Rgba r = {255, 0, 0, 255}, g = {0, 255, 0, 255}, b = {0, 0, 255, 255},
                   o = {0x10, 0x20, 0x30, 255};
        require_pixels(read_image(dir.path("pal.png")), 5, 2, {r, g, b, o, o, b, g, r, g, g});
    }
}

TEST_CASE("PNG files whose data or size lie are refused with the numbers", "[image][bad]") {
    TempDir dir;
    auto error = [&](const std::string& name, const std::string& bytes) {
        write_bytes(dir.path(name), bytes);
        const std::string msg = image_error(dir.path(name));
        REQUIRE_THAT(msg, Contains(name));
        return msg;
    };
    SECTION("16384 x 16384 grey pixels (a 268 Mpixel image in a small file)") {
        // The image data of one row; the header alone is refused.
        const std::string z = zlib_compress(std::string(16385, '\0'));
        CHECK_THAT(error("big.png", png_file(16384, 16384, 8, 0, z)),
                   Contains("image size 16384 x 16384 (268435456 pixels) exceeds the limit of "
                            "67108864 pixels (64 Mpixel)"));
    }
    SECTION("a 1 x 1 image whose data inflates to 64 MiB") {
        z_stream zs{};
        REQUIRE(deflateInit(&zs, 9) == Z_OK);
        std::string zeros(1 << 20, '\0'), out;
        std::vector<unsigned char> buf(1 << 16);
        for (int i = 0; i <= 64; ++i) {
            zs.next_in = reinterpret_cast<Bytef*>(&zeros[0]);
            zs.avail_in = i < 64 ? uInt(zeros.size()) : 0;
            const int flush = i < 64 ? Z_NO_FLUSH : Z_FINISH;
            do {
                zs.next_out = buf.data();
                zs.avail_out = uInt(buf.size());
                deflate(&zs, flush);
                out.append(reinterpret_cast<char*>(buf.data()), buf.size() - zs.avail_out);
            } while (zs.avail_out == 0);
        }
        deflateEnd(&zs);
        REQUIRE(out.size() < 200000);
        CHECK_THAT(error("bomb.png", png_file(1, 1, 8, 0, out, false, 8192)),
                   Contains("the PNG image data inflates past the 2 bytes that its 1 x 1 pixels "
                            "(colour type 0, 8 bits) declare"));
    }
    SECTION("data that ends early, is not zlib data, or is missing") {
        const std::string raw = scanlines(4, 4, 1, 8, std::vector<unsigned>(16, 7), false);
        CHECK_THAT(error("short.png", png_file(4, 4, 8, 0, zlib_compress(raw.substr(0, 10)))),
                   Contains("truncated PNG: the image data ends after 10 of the 20 bytes"));
        const std::string z = zlib_compress(raw);
        CHECK_THAT(error("cut.png", png_file(4, 4, 8, 0, z.substr(0, z.size() / 2))),
                   Contains("truncated PNG: the image data ends after"));
        CHECK_THAT(error("garbage.png", png_file(4, 4, 8, 0, std::string(40, '\x55'))),
                   Contains("corrupt PNG image data (zlib: "));
        CHECK_THAT(error("none.png", png_file(4, 4, 8, 0, "")),
                   Contains("truncated PNG: no image data"));
        CHECK_THAT(error("depth.png", png_file(4, 4, 3, 0, z)), Contains("bit depth 3"));
    }
}

// ---- RLE BMP --------------------------------------------------------------------------------

namespace {

std::string le32(std::uint32_t v) {
    return {char(v), char(v >> 8), char(v >> 16), char(v >> 24)};
}
std::string le16(std::uint32_t v) {
    return {char(v), char(v >> 8)};
}

/// A BMP with a 40-byte info header, a palette (R, G, B) and RLE data.
std::string rle_bmp(std::int32_t width, std::int32_t height, int bpp, int compression,
                    const std::vector<Rgba>& palette, const std::string& data) {
    const std::uint32_t offset = 14 + 40 + 4 * std::uint32_t(palette.size());
    std::string out = "BM" + le32(offset + std::uint32_t(data.size())) + le32(0) + le32(offset);
    out += le32(40) + le32(std::uint32_t(width)) + le32(std::uint32_t(height)) + le16(1) +
           le16(std::uint32_t(bpp)) + le32(std::uint32_t(compression)) +
           le32(std::uint32_t(data.size())) + le32(2835) + le32(2835) +
           le32(std::uint32_t(palette.size())) + le32(0);
    for (const Rgba& c : palette) out += {char(c[2]), char(c[1]), char(c[0]), '\0'};
    return out + data;
}

std::string bytes(std::initializer_list<int> values) {
    std::string out;
    for (int v : values) out += char(v);
    return out;
}

const Rgba kRed = {255, 0, 0, 255}, kGreen = {0, 255, 0, 255}, kBlue = {0, 0, 255, 255},
           kWhite = {255, 255, 255, 255}, kSkipped = {0, 0, 0, 0};

}  // namespace

TEST_CASE("RLE8 and RLE4 BMP files are read with exact pixels", "[image]") {
    TempDir dir;
    const std::vector<Rgba> palette = {kRed, kGreen, kBlue, kWhite};
    SECTION("RLE8: runs, an absolute run with padding, delta, end of line and of bitmap") {
        const std::string data = bytes({
            3, 1, 1, 2, 0, 0,        // bottom row: 3 x green, 1 x blue; end of line
            0, 3, 0, 1, 2, 0, 0, 0,  // absolute: red, green, blue (+ pad); end of line
            0, 2, 2, 0, 2, 3, 0, 1,  // delta 2 right; 2 x white; end of bitmap
        });
        write_bytes(dir.path("rle8.bmp"), rle_bmp(4, 3, 8, 1, palette, data));
        require_pixels(read_image(dir.path("rle8.bmp")), 4, 3,
                       {kSkipped, kSkipped, kWhite, kWhite,  // top row
                        kRed, kGreen, kBlue, kSkipped,       // middle
                        kGreen, kGreen, kGreen, kBlue});     // bottom
    }
    SECTION("RLE8: a delta up skips a row, end of bitmap leaves the rest") {
        // 2 x white, end of line, delta 1 up, 1 x red, end of bitmap.
        const std::string data = bytes({2, 3, 0, 0, 0, 2, 0, 1, 1, 0, 0, 1});
        write_bytes(dir.path("skip.bmp"), rle_bmp(2, 4, 8, 1, palette, data));
        require_pixels(read_image(dir.path("skip.bmp")), 2, 4,
                       {kSkipped, kSkipped, kRed, kSkipped, kSkipped, kSkipped, kWhite, kWhite});
    }
    SECTION("RLE4: alternating runs and absolute runs of odd length") {
        const std::string data = bytes({
            5, 0x12, 0, 0,                    // bottom: green blue green blue green
            0, 5, 0x01, 0x23, 0x00, 0, 0, 1,  // absolute: red green blue white red (+ pad)
        });
        write_bytes(dir.path("rle4.bmp"), rle_bmp(5, 2, 4, 2, palette, data));
        require_pixels(read_image(dir.path("rle4.bmp")), 5, 2,
                       {kRed, kGreen, kBlue, kWhite, kRed, kGreen, kBlue, kGreen, kBlue, kGreen});
    }
    SECTION("broken RLE data is refused naming the reason") {
        struct Case {
            const char* name;
            std::string file;
            const char* reason;
        };
        const std::vector<Case> cases = {
            {"long_run.bmp", rle_bmp(4, 2, 8, 1, palette, bytes({5, 1, 0, 1})),
             "runs past the end of row 0"},
            {"too_many_rows.bmp", rle_bmp(2, 1, 8, 1, palette, bytes({2, 1, 0, 0, 1, 1, 0, 1})),
             "runs past the last row"},
            {"index.bmp", rle_bmp(2, 1, 8, 1, palette, bytes({1, 9, 0, 1})),
             "palette index 9 at byte"},
            {"no_end.bmp", rle_bmp(2, 2, 8, 1, palette, bytes({2, 1, 0, 0})),
             "before the end-of-bitmap escape"},
            {"cut_absolute.bmp", rle_bmp(8, 1, 8, 1, palette, bytes({0, 5, 1, 1})),
             "before the end-of-bitmap escape"},
            {"delta.bmp", rle_bmp(2, 2, 8, 1, palette, bytes({0, 2, 3, 0, 0, 1})), "delta at byte"},
            {"top_down.bmp", rle_bmp(2, -2, 8, 1, palette, bytes({0, 1})), "top-down"},
            {"bpp.bmp", rle_bmp(2, 2, 4, 1, palette, bytes({0, 1})),
             "RLE8 compression needs 8 bits per pixel, the header says 4"},
            {"big_palette.bmp", rle_bmp(2, 2, 4, 2, std::vector<Rgba>(17, kRed), bytes({0, 1})),
             "17 palette colours"},
        };
        for (const Case& c : cases) {
            INFO(c.name);
            write_bytes(dir.path(c.name), c.file);
            CHECK_THAT(image_error(dir.path(c.name)), Contains(c.name) && Contains(c.reason));
        }
    }
}

// ---- XPM: every X11 colour name -------------------------------------------------------------

TEST_CASE("XPM reads every colour name of X11's rgb.txt, ignoring case and spaces", "[image]") {
    const std::string rgb_txt = "/usr/share/X11/rgb.txt";
    if (!exists(rgb_txt)) {
        SKIP_TEST(rgb_txt << " (x11-common) is absent");
    }
    // Every line of the table as it is written there (names with spaces included), as the
    // colours of one row of pixels, three characters per pixel.
    std::ifstream in(rgb_txt);
    std::vector<std::pair<std::string, Rgba>> names;
    for (std::string line; std::getline(in, line);) {
        std::istringstream fields(line);
        int r, g, b;
        if (line.empty() || line[0] == '!' || !(fields >> r >> g >> b)) continue;
        std::string name;
        std::getline(fields >> std::ws, name);
        while (!name.empty() && std::isspace(static_cast<unsigned char>(name.back())))
            name.pop_back();
        names.push_back({name, {r, g, b, 255}});
    }
    REQUIRE(names.size() > 700);
    auto code = [](std::size_t i) {
        const char* digits = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ";
        return std::string{digits[i / (52 * 52) % 52], digits[i / 52 % 52], digits[i % 52]};
    };
    auto upper = [](std::string s) {
        for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
        return s;
    };
    TempDir dir;
    std::string xpm = "/* XPM */\nstatic char *all[] = {\n\"" + std::to_string(names.size()) +
                      " 1 " + std::to_string(names.size()) + " 3\",\n";
    std::string row;
    Pixels expected;
    for (std::size_t i = 0; i < names.size(); ++i) {
        // Every third name in upper case: X11 ignores case.
        const std::string name = i % 3 == 0 ? upper(names[i].first) : names[i].first;
        xpm += "\"" + code(i) + " c " + name + "\",\n";
        row += code(i);
        expected.push_back(names[i].second);
    }
    xpm += "\"" + row + "\"\n};\n";
    write_bytes(dir.path("all.xpm"), xpm);
    require_pixels(read_image(dir.path("all.xpm")), int(names.size()), 1, expected);
}

TEST_CASE("XPM in the layout ImageMagick writes, with X11 colour names", "[image]") {
    // names_imagemagick.xpm: written by hand in the layout of ImageMagick 6's `convert x.png
    // x.xpm` (comments, a trailing space on the values line, names where a colour has one),
    // which the reader used to refuse with "unknown colour 'snow'".
    const Rgba snow = {255, 250, 250, 255}, slate = {47, 79, 79, 255}, g50 = {127, 127, 127, 255},
               gold2 = {238, 220, 130, 255}, dodger = {30, 144, 255, 255};
    require_pixels(read_image(image_file("names_imagemagick.xpm")), 6, 4,
                   {snow, snow,  snow, snow,  snow,   snow,  //
                    snow, slate, snow, snow,  dodger, snow,  //
                    snow, snow,  g50,  snow,  snow,   snow,  //
                    snow, snow,  snow, gold2, snow,   snow});
    TempDir dir;
    const std::vector<std::pair<std::string, Rgba>> spellings = {
        {"SNOW", snow}, {"Dark Slate Gray", slate}, {"darkSLATEgrey", slate}, {"Gray50", g50}};
    for (const auto& [spelling, rgba] : spellings) {
        INFO(spelling);
        write_bytes(dir.path("one.xpm"), "/* XPM */\nstatic char* c[] = {\"1 1 1 1\", \"x c " +
                                             spelling + "\", \"x\"};\n");
        require_pixels(read_image(dir.path("one.xpm")), 1, 1, {rgba});
    }
    write_bytes(dir.path("bad.xpm"),
                "/* XPM */\nstatic char* c[] = {\"1 1 1 1\", \"x c snowy\", \"x\"};\n");
    CHECK_THAT(image_error(dir.path("bad.xpm")),
               Contains("unknown colour 'snowy' (neither None, #hex, nor one of the"));
}
