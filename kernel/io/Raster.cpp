#include "io/Raster.h"

#include "model/Error.h"

#include <algorithm>
#include <cmath>
#include <utility>

// stb's implementations are compiled here with static linkage, so they cannot clash with another
// copy elsewhere in a program (tinygltf is built without its own stb, see GltfExport.cpp).
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_easy_font.h>
#include <stb/stb_image_write.h>

namespace netsculpt::io {

RasterCanvas::RasterCanvas(int width, int height)
    : width_(width), height_(height), pixels_(std::size_t(width) * std::size_t(height) * 3, 1.0f) {}

void RasterCanvas::blend(int x, int y, const Rgb& colour, double alpha) {
    if (x < 0 || y < 0 || x >= width_ || y >= height_ || alpha <= 0)
        return;
    alpha = std::min(alpha, 1.0);
    float* p = &pixels_[(std::size_t(y) * std::size_t(width_) + std::size_t(x)) * 3];
    p[0] = float(p[0] + (colour.r - p[0]) * alpha);
    p[1] = float(p[1] + (colour.g - p[1]) * alpha);
    p[2] = float(p[2] + (colour.b - p[2]) * alpha);
}

namespace {

/// The pixel index of coordinate `v`, clamped to [-1, limit] before the conversion, so that a
/// coordinate far off the canvas (even past int's range) neither overflows nor widens a loop;
/// NaN gives -1.
int clampedPixel(double v, int limit) {
    return v > -1 ? int(std::min(v, double(limit))) : -1;
}

/// The x range [lo, hi] that a stroke of `reach` around the segment (x0, y0)-(x1, y1) can touch
/// within the pixel row [y, y + 1]; empty (lo > hi) when the stroke misses the row.
std::pair<double, double> rowSpan(double x0, double y0, double x1, double y1, double reach, int y) {
    const double dy = y1 - y0;
    double t0 = 0, t1 = 1; // the part of the segment within `reach` of the row
    if (dy != 0) {
        t0 = std::clamp((y - reach - y0) / dy, 0.0, 1.0);
        t1 = std::clamp((y + 1 + reach - y0) / dy, 0.0, 1.0);
        if (t0 > t1)
            std::swap(t0, t1);
    }
    const double yMin = std::min(y0, y1), yMax = std::max(y0, y1);
    if (yMax < y - reach || yMin > y + 1 + reach)
        return {1, 0};
    const double xa = x0 + t0 * (x1 - x0), xb = x0 + t1 * (x1 - x0);
    return {std::min(xa, xb) - reach, std::max(xa, xb) + reach};
}

} // namespace

void RasterCanvas::line(double x0, double y0, double x1, double y1, const Rgb& colour,
                        double width) {
    if (!(std::isfinite(x0) && std::isfinite(y0) && std::isfinite(x1) && std::isfinite(y1)))
        return;
    // Strokes thinner than a pixel are drawn one pixel wide and fainter (their ink per length).
    const double half = 0.5 * std::max(width, 1.0);
    const double opacity = std::min(width, 1.0);
    const double reach = half + 1;
    const int ya = std::max(0, clampedPixel(std::floor(std::min(y0, y1) - reach), height_));
    const int yb =
        std::min(height_ - 1, clampedPixel(std::ceil(std::max(y0, y1) + reach), height_));
    const double dx = x1 - x0, dy = y1 - y0, lengthSq = dx * dx + dy * dy;
    // Row by row, only the pixels near the stroke: the work follows the stroke's length on the
    // canvas, not the area of its bounding box (a long diagonal would visit the whole canvas).
    for (int y = ya; y <= yb; ++y) {
        const auto [lo, hi] = rowSpan(x0, y0, x1, y1, reach, y);
        const int xa = std::max(0, clampedPixel(std::floor(lo), width_));
        const int xb = std::min(width_ - 1, clampedPixel(std::ceil(hi), width_));
        for (int x = xa; x <= xb; ++x) {
            const double px = x + 0.5 - x0, py = y + 0.5 - y0;
            const double t =
                lengthSq > 0 ? std::clamp((px * dx + py * dy) / lengthSq, 0.0, 1.0) : 0.0;
            const double ex = px - t * dx, ey = py - t * dy;
            const double coverage = std::clamp(half + 0.5 - std::sqrt(ex * ex + ey * ey), 0.0, 1.0);
            if (coverage > 0)
                blend(x, y, colour, coverage * opacity);
        }
    }
}

void RasterCanvas::rect(double x, double y, double w, double h, const Rgb& colour) {
    const int xa = std::max(0, clampedPixel(std::floor(x), width_)),
              xb = std::min(width_ - 1, clampedPixel(std::ceil(x + w), width_) - 1);
    const int ya = std::max(0, clampedPixel(std::floor(y), height_)),
              yb = std::min(height_ - 1, clampedPixel(std::ceil(y + h), height_) - 1);
    for (int py = ya; py <= yb; ++py) {
        const double cy = std::min(py + 1.0, y + h) - std::max(double(py), y);
        for (int px = xa; px <= xb; ++px) {
            const double cx = std::min(px + 1.0, x + w) - std::max(double(px), x);
            blend(px, py, colour, std::max(0.0, cx) * std::max(0.0, cy));
        }
    }
}

void RasterCanvas::disc(double x, double y, double radius, const Rgb& colour) {
    const int xa = std::max(0, clampedPixel(std::floor(x - radius - 1), width_)),
              xb = std::min(width_ - 1, clampedPixel(std::ceil(x + radius + 1), width_));
    const int ya = std::max(0, clampedPixel(std::floor(y - radius - 1), height_)),
              yb = std::min(height_ - 1, clampedPixel(std::ceil(y + radius + 1), height_));
    for (int py = ya; py <= yb; ++py)
        for (int px = xa; px <= xb; ++px) {
            const double d = std::hypot(px + 0.5 - x, py + 0.5 - y);
            blend(px, py, colour, std::clamp(radius + 0.5 - d, 0.0, 1.0));
        }
}

namespace {

/// stb_easy_font's vertex: x, y, z, then RGBA bytes (16 bytes); 4 per quad.
struct FontVertex {
    float x, y, z;
    unsigned char rgba[4];
};
static_assert(sizeof(FontVertex) == 16);

/// `text` in the glyphs stb_easy_font has: printable ASCII and line breaks. It indexes its glyph
/// table by `c - 32` with a signed char, so any other byte (a name in UTF-8, a control character)
/// would read outside the table; each such character becomes one '?'.
std::string fontText(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    bool inSequence = false; // after a UTF-8 lead byte, its continuation bytes are skipped
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte >= 0x80 && byte < 0xc0 && inSequence)
            continue;
        inSequence = byte >= 0xc0;
        out += (byte == '\n' || (byte >= 32 && byte < 127)) ? c : '?';
    }
    return out;
}

} // namespace

void RasterCanvas::text(double x, double y, const std::string& text, double scale,
                        const Rgb& colour) {
    std::vector<FontVertex> buffer(std::max<std::size_t>(64, text.size() * 300));
    std::string copy = fontText(text);
    unsigned char rgba[4] = {0, 0, 0, 255};
    const int quads = stb_easy_font_print(0, 0, copy.data(), rgba, buffer.data(),
                                          int(buffer.size() * sizeof(FontVertex)));
    for (int q = 0; q < quads; ++q) {
        const FontVertex& a = buffer[std::size_t(q) * 4];
        const FontVertex& c = buffer[std::size_t(q) * 4 + 2];
        rect(x + a.x * scale, y + a.y * scale, (c.x - a.x) * scale, (c.y - a.y) * scale, colour);
    }
}

double RasterCanvas::textWidth(const std::string& text, double scale) const {
    std::string copy = fontText(text);
    return stb_easy_font_width(copy.data()) * scale;
}

std::vector<std::uint8_t> RasterCanvas::rgb8() const {
    std::vector<std::uint8_t> out(pixels_.size());
    for (std::size_t i = 0; i < pixels_.size(); ++i)
        out[i] = std::uint8_t(std::lround(std::clamp(double(pixels_[i]), 0.0, 1.0) * 255.0));
    return out;
}

namespace {
void appendBytes(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size));
}
} // namespace

std::string encodePng(const std::vector<std::uint8_t>& rgb, int width, int height) {
    std::string bytes;
    if (!stbi_write_png_to_func(appendBytes, &bytes, width, height, 3, rgb.data(), width * 3))
        throw UserError("PNG encoding failed (" + std::to_string(width) + " x " +
                        std::to_string(height) + " px)");
    return bytes;
}

} // namespace netsculpt::io
