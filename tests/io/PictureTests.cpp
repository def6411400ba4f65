// Pictures (svg, png): the PNG has the asked size, is not blank, and the net is drawn where the
// views project its knots; the SVG holds every bar in every view; tension colours.

#include "IoTestSupport.h"

#include "io/Canvas.h"
#include "io/Export.h"
#include "io/Raster.h"
#include "io/Scene.h"
#include "io/Views.h"

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>

using namespace netsculpt;
using namespace netsculpt::test;
using Catch::Matchers::Contains;

namespace {

struct Image {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;
    io::Rgb at(int x, int y) const {
        const unsigned char* p = &rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
        return {p[0] / 255.0, p[1] / 255.0, p[2] / 255.0};
    }
};

Image load(const std::filesystem::path& file) {
    Image image;
    int channels = 0;
    std::unique_ptr<unsigned char, void (*)(void*)> data(
        stbi_load(file.c_str(), &image.width, &image.height, &channels, 3), stbi_image_free);
    REQUIRE(data);
    image.rgb.assign(data.get(),
                     data.get() + std::size_t(image.width) * std::size_t(image.height) * 3);
    return image;
}

double difference(const io::Rgb& a, const io::Rgb& b) {
    return std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b);
}

/// The most ink (difference from the background) within `radius` px of (x, y).
double inkNear(const Image& image, double x, double y, int radius = 1) {
    double ink = 0;
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
            const int px = int(std::floor(x)) + dx, py = int(std::floor(y)) + dy;
            if (px >= 0 && py >= 0 && px < image.width && py < image.height)
                ink = std::max(ink, difference(image.at(px, py), io::kBackground));
        }
    return ink;
}

} // namespace

TEST_CASE("PNG: the asked size, not blank, the net where the view projects its knots") {
    SheetNet t = sheet(8, 7, 1.5, 0.25);
    ExportOptions options;
    options.view = "top";
    options.width = 480;
    options.height = 360;
    const auto dir = outputDir("png");
    exportFile(t.s, t.compiled, {}, dir / "top.png", options);
    const Image image = load(dir / "top.png");
    CHECK(image.width == 480);
    CHECK(image.height == 360);
    std::size_t inked = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            inked += difference(image.at(x, y), io::kBackground) > 0.05;
    CHECK(inked > 2000);
    CHECK(inked < std::size_t(image.width * image.height) / 2);

    // The top view: x to the right, y up. Seen from above the unrelaxed sheet hangs straight
    // below its rail, so the rail hides it: the rail's middle is nearly the rail colour.
    const io::Scene scene = io::buildScene(t.s, t.compiled, "piece", false);
    const io::Panel top = io::layoutFor(scene, "top", image.width, image.height).panels.at(0);
    const io::ScreenPoint left = top.project({0, 0, 0}), right = top.project({1.5, 0, 0}),
                          up = top.project({0, 1, 0});
    CHECK(right.x > left.x);
    CHECK(up.y < left.y);
    CHECK(right.x - left.x > 0.6 * image.width);
    CHECK(inkNear(image, left.x, left.y) > 0.3);
    CHECK(inkNear(image, right.x, right.y) > 0.3);
    CHECK(difference(image.at(int((left.x + right.x) / 2), int(left.y)), io::kRailColour) < 0.3);
    CHECK(inkNear(image, left.x, left.y + 0.3 * image.height, 2) < 0.01); // 8-bit rounding

    // Front view: every knot below the rail is drawn, in the piece's colour, where the view puts
    // it; the middle of each mesh diamond (between knots (r, c) and (r + 2, c)) is background.
    options.view = "front";
    exportFile(t.s, t.compiled, {}, dir / "front.png", options);
    const Image front = load(dir / "front.png");
    const io::Panel panel = io::layoutFor(scene, "front", front.width, front.height).panels.at(0);
    const io::Rgb colour = io::toSrgb(t.s.piece(t.piece).colour);
    const auto& pk = t.compiled.pieces.at(t.piece);
    const auto& position = t.compiled.system.position;
    for (int r = 1; r < pk.rows; ++r)
        for (int c = 0; c < pk.columns; ++c) {
            const io::ScreenPoint s = panel.project(position[pk.at(r, c)]);
            INFO("knot " << r << ", " << c << " at " << s.x << ", " << s.y);
            double nearest = 9;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    nearest = std::min(nearest,
                                       difference(front.at(int(s.x) + dx, int(s.y) + dy), colour));
            // At least half covered by the piece's colour (an edge knot has a single 1-px bar).
            CHECK(nearest < 0.5 * difference(colour, io::kBackground));
            if (r % 2 == 0 && r + 2 < pk.rows && c > 0) {
                const io::ScreenPoint m =
                    panel.project((position[pk.at(r, c)] + position[pk.at(r + 2, c)]) * 0.5);
                CHECK(inkNear(front, m.x, m.y, 2) < 0.01);
            }
        }
    const io::ScreenPoint a = panel.project(position[pk.at(0, 3)]),
                          b = panel.project(position[pk.at(pk.rows - 1, 3)]);
    CHECK(b.y > a.y + 0.4 * front.height); // rows go down the picture
}

TEST_CASE("PNG strokes to points far off the canvas are drawn up to its edge") {
    // A diverged shape can put knots 1e12 px away; the visible part of their bars still shows.
    io::RasterCanvas canvas(64, 64);
    canvas.line(10, 20, 1e12, 20, io::Rgb{}, 2);
    canvas.line(40, 1e15, 40, -1e15, io::Rgb{}, 2);
    canvas.line(-1e12, -1e12, 1e12, 1e12, io::Rgb{}, 2); // the diagonal
    const Image image{64, 64, canvas.rgb8()};
    const auto inked = [&](int x, int y) { return image.at(x, y).r < 0.5; };
    CHECK(inked(10, 20));
    CHECK(inked(30, 20));
    CHECK(inked(63, 20));
    CHECK(inked(40, 0));
    CHECK(inked(40, 63));
    CHECK(inked(5, 5));
    CHECK(inked(60, 60));
    CHECK_FALSE(inked(5, 20));
    CHECK_FALSE(inked(20, 50));
}

TEST_CASE("PNG text outside printable ASCII is drawn as one '?' per character") {
    // stb_easy_font indexes its glyphs by char - 32: a UTF-8 name (or a control character)
    // read outside its table (an AddressSanitizer report on `netsculpt export x.png`).
    io::RasterCanvas canvas(200, 40), expected(200, 40);
    const std::string name = "r\xc3\xa9seau \xe4\xb8\xad\x01\x7f";
    CHECK(canvas.textWidth(name, 1) == expected.textWidth("r?seau ???", 1));
    CHECK(canvas.textWidth(name, 1) > 0);
    canvas.text(2, 2, name, 1, io::Rgb{});
    expected.text(2, 2, "r?seau ???", 1, io::Rgb{});
    CHECK(canvas.rgb8() == expected.rgb8());

    Tube t = tubeWithChild(16, 6, 1.2, 0.35);
    t.s.pieces.at(t.child).name = "\xe7\xbd\x91 \xc3\xa9\ttab";
    const auto file = outputDir("png-names") / "names.png";
    exportFile(t.s, t.compiled, {}, file);
    CHECK(load(file).width == 1600);
}

TEST_CASE("PNG sheet of all four views: each panel holds a drawing") {
    Tube t = tubeWithChild(16, 6, 1.2, 0.35);
    const auto file = outputDir("png-sheet") / "sheet.png";
    exportFile(t.s, t.compiled, {}, file);
    const Image image = load(file);
    REQUIRE(image.width == 1600);
    REQUIRE(image.height == 1200);
    const io::Scene scene = io::buildScene(t.s, t.compiled, "piece", false);
    const io::Sheet sheet = io::layoutFor(scene, "all", image.width, image.height);
    REQUIRE(sheet.panels.size() == 4);
    const io::Rgb childColour = io::toSrgb(Colour{0.1, 0.3, 0.8});
    for (const io::Panel& panel : sheet.panels) {
        INFO(panel.camera.name);
        std::size_t inked = 0, child = 0;
        for (int y = int(panel.top + panel.drawTop); y < int(panel.top + panel.height); ++y)
            for (int x = int(panel.left); x < int(panel.left + panel.width); ++x) {
                inked += difference(image.at(x, y), io::kBackground) > 0.05;
                child += difference(image.at(x, y), childColour) < 0.08;
            }
        CHECK(inked > 5000);
        CHECK(child > 200); // the child piece is drawn in its own colour
        // Its lowest knot projects onto ink.
        const auto& pk = t.compiled.pieces.at(t.child);
        const io::ScreenPoint s = panel.project(t.compiled.system.position[pk.at(pk.rows - 1, 5)]);
        CHECK(inkNear(image, s.x, s.y) > 0.3);
    }
}

TEST_CASE("SVG: every bar in every view, in its piece's colour, with title and scale bars") {
    SheetNet t = sheet(5, 4, 1.0, 0.3);
    const auto file = outputDir("svg") / "net.svg";
    exportFile(t.s, t.compiled, {}, file);
    const std::string svg = readText(file);
    CHECK(svg.rfind("<?xml", 0) == 0);
    CHECK_THAT(
        svg, Contains("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"1600\" height=\"1200\""));
    CHECK_THAT(svg, Contains("netsculpt - 1 piece, 20 knots, 28 bars, not relaxed"));
    for (const auto& view : io::viewNames())
        CHECK_THAT(svg, Contains("<g id=\"view-" + view + "\">"));
    const io::Rgb c = io::toSrgb(t.s.piece(t.piece).colour);
    char hex[8];
    std::snprintf(hex, sizeof hex, "#%02x%02x%02x", int(std::lround(c.r * 255)),
                  int(std::lround(c.g * 255)), int(std::lround(c.b * 255)));
    std::size_t bars = 0;
    for (std::size_t at = svg.find(std::string("stroke=\"") + hex); at != std::string::npos;
         at = svg.find(std::string("stroke=\"") + hex, at + 1))
        ++bars;
    CHECK(bars == 4 * t.compiled.system.barCount());
    CHECK_THAT(svg, Contains(">50 cm</text>")); // scale bar of the 1 m sheet
}

TEST_CASE("SVG text: characters XML forbids and bytes that are not UTF-8 are written as '?'") {
    SheetNet t = sheet(5, 4, 1.0, 0.3);
    // A name set from a script may hold any bytes: a control character, a lone continuation
    // byte, a truncated sequence and an overlong one around valid UTF-8.
    t.s.pieces.at(t.piece).name = "r\xc3\xa9seau\x01\x80<\xe4\xb8\xad\xe4\xb8 \xc0\xaf\x7f";
    const auto file = outputDir("svg-names") / "names.svg";
    exportFile(t.s, t.compiled, {}, file);
    const std::string svg = readText(file);
    CHECK_THAT(svg, Contains("r\xc3\xa9seau??&lt;\xe4\xb8\xad?? ??\x7f"));
    const auto forbidden = std::count_if(svg.begin(), svg.end(), [](char c) {
        return static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t' && c != '\r';
    });
    CHECK(forbidden == 0);
}

TEST_CASE("tension colours: the most tensioned bar at the ramp's end, slack bars grey") {
    SheetNet t = sheet(6, 5, 1.0, 0.25, /*soft=*/true);
    RelaxOptions options;
    options.tolerance = 1e-6;
    REQUIRE(relaxRk4(t.compiled.system, options).converged);
    const io::Scene scene = io::buildScene(t.s, t.compiled, "tension", true);
    REQUIRE(scene.maxTension > 0);
    std::size_t strongest = 0;
    for (std::size_t b = 0; b < scene.tension.size(); ++b)
        if (scene.tension[b] > scene.tension[strongest])
            strongest = b;
    const io::Rgb end = io::tensionColour(1);
    CHECK(difference(scene.segments[strongest].colour, end) < 1e-12);
    CHECK(scene.legend.size() == 3);
    CHECK_THROWS_WITH(io::buildScene(t.s, t.compiled, "weight", true),
                      Contains("\"piece\" or \"tension\""));

    // Squeeze one bar below its rest length: it is drawn grey.
    auto& sys = t.compiled.system;
    const std::size_t b = sys.barCount() - 1;
    sys.position[sys.barA[b]] = sys.position[sys.barB[b]] + Vec3{0, 0, -0.5 * sys.restLength[b]};
    const io::Scene squeezed = io::buildScene(t.s, t.compiled, "tension", false);
    CHECK(difference(squeezed.segments[b].colour, io::kSlackColour) == 0);
}
