#include "io/Canvas.h"
#include "io/IoText.h"

#include <algorithm>
#include <cmath>

namespace netsculpt::io {

namespace {

constexpr Rgb kText{0.12, 0.12, 0.14};
constexpr Rgb kMuted{0.45, 0.45, 0.48};
constexpr Rgb kFrame{0.82, 0.82, 0.80};
constexpr std::size_t kMaxLegendPieces = 8;

std::vector<Vec3> scenePoints(const Scene& scene) {
    std::vector<Vec3> points;
    points.reserve(2 * scene.segments.size() + scene.heldKnots.size());
    for (const auto& seg : scene.segments) {
        points.push_back(seg.a);
        points.push_back(seg.b);
    }
    points.insert(points.end(), scene.heldKnots.begin(), scene.heldKnots.end());
    return points;
}

/// The legend, right-aligned in the title bar between `left` (the title's end) and `right`:
/// swatches and labels (pieces, as many as fit, then "+N more"), or the tension ramp.
void drawLegend(Canvas& canvas, const Scene& scene, double left, double right, double top, double s) {
    const double swatch = 7 * s, gap = 4 * s;
    double x = right;
    const auto entry = [&](const std::string& label, const Rgb& colour) {
        x -= canvas.textWidth(label, s);
        canvas.text(x, top, label, s, kText);
        x -= gap + swatch;
        canvas.rect(x, top, swatch, swatch, colour);
        x -= 3 * gap;
    };
    if (scene.colourBy == "tension") {
        entry("slack", kSlackColour);
        const std::string high = scene.legend.size() > 1 ? scene.legend[1].label : "";
        x -= canvas.textWidth(high, s);
        canvas.text(x, top, high, s, kText);
        const double rampWidth = 60 * s;
        x -= gap + rampWidth;
        const int steps = 48;
        for (int i = 0; i < steps; ++i)
            canvas.rect(x + rampWidth * i / steps, top, rampWidth / steps + 0.5, swatch,
                        tensionColour((i + 0.5) / steps));
        x -= gap;
        const std::string low = "tension 0 N";
        x -= canvas.textWidth(low, s);
        canvas.text(x, top, low, s, kText);
        return;
    }
    const auto entryWidth = [&](std::size_t i) {
        return canvas.textWidth(scene.legend[i].label, s) + 4 * gap + swatch;
    };
    std::size_t shown = std::min(scene.legend.size(), kMaxLegendPieces);
    const double moreWidth = canvas.textWidth("+99 more", s) + 3 * gap;
    for (;;) {
        double width = shown < scene.legend.size() ? moreWidth : 0;
        for (std::size_t i = 0; i < shown; ++i) width += entryWidth(i);
        if (shown == 0 || right - width >= left) break;
        --shown;
    }
    if (scene.legend.size() > shown) {
        const std::string more =
            concat({"+", std::to_string(scene.legend.size() - shown), " more"});
        x -= canvas.textWidth(more, s);
        canvas.text(x, top, more, s, kMuted);
        x -= 3 * gap;
    }
    for (std::size_t i = shown; i-- > 0;)
        entry(scene.legend[i].label, scene.legend[i].colour);
}

void drawScaleBar(Canvas& canvas, const Panel& panel, double s) {
    const double maxMetres = 0.28 * panel.width / panel.scale;
    const double metres = niceLength(maxMetres);
    const double length = metres * panel.scale;
    const double x0 = panel.left + 10 * s, y = panel.top + panel.height - 9 * s;
    canvas.line(x0, y, x0 + length, y, kText, 1.2 * s);
    canvas.line(x0, y - 3 * s, x0, y + 0.5 * s, kText, 1.2 * s);
    canvas.line(x0 + length, y - 3 * s, x0 + length, y + 0.5 * s, kText, 1.2 * s);
    canvas.text(x0, y - 13 * s, lengthLabel(metres), s, kText);
}

} // namespace

Sheet layoutFor(const Scene& scene, const std::string& view, int width, int height) {
    Sheet sheet;
    sheet.textScale = std::max(1.0, std::round(std::min(width, height) / 600.0));
    const double s = sheet.textScale;
    sheet.titleHeight = std::min(22 * s, 0.25 * height);
    sheet.panels =
        layoutSheet(view, width, height, sheet.titleHeight, std::min(16 * s, 0.15 * height),
                    scenePoints(scene), scene.lo, scene.hi);
    return sheet;
}

void drawSheet(Canvas& canvas, const Scene& scene, const Sheet& sheet, int width, int height) {
    const double s = sheet.textScale;
    canvas.rect(0, 0, width, height, kBackground);
    canvas.text(8 * s, 7 * s, scene.title, s, kText);
    drawLegend(canvas, scene, 8 * s + canvas.textWidth(scene.title, s) + 16 * s, width - 8 * s, 7 * s, s);
    canvas.line(0, sheet.titleHeight, width, sheet.titleHeight, kFrame, 1);

    const double barWidth = std::max(1.0, 0.65 * s), railWidth = 2.6 * barWidth;
    for (const Panel& panel : sheet.panels) {
        canvas.beginGroup("view-" + panel.camera.name);
        if (sheet.panels.size() > 1) {
            canvas.line(panel.left + panel.width, panel.top, panel.left + panel.width,
                        panel.top + panel.height, kFrame, 1);
            canvas.line(panel.left, panel.top + panel.height, panel.left + panel.width,
                        panel.top + panel.height, kFrame, 1);
        }
        canvas.text(panel.left + 8 * s, panel.top + 5 * s,
                    panel.camera.name + (panel.camera.perspective ? "" : " view"), s, kMuted);
        struct Item {
            ScreenPoint a, b;
            const SceneSegment* seg;
        };
        std::vector<Item> items;
        items.reserve(scene.segments.size());
        for (const auto& seg : scene.segments)
            items.push_back({panel.project(seg.a), panel.project(seg.b), &seg});
        std::stable_sort(items.begin(), items.end(), [](const Item& p, const Item& q) {
            return p.a.depth + p.b.depth > q.a.depth + q.b.depth; // far first
        });
        for (const Item& item : items)
            canvas.line(item.a.x, item.a.y, item.b.x, item.b.y, item.seg->colour,
                        item.seg->rail ? railWidth : barWidth);
        for (const Vec3& p : scene.heldKnots) {
            const ScreenPoint q = panel.project(p);
            canvas.disc(q.x, q.y, 1.7 * barWidth, kRailColour);
        }
        if (!panel.camera.perspective)
            drawScaleBar(canvas, panel, s);
        canvas.endGroup();
    }
}

} // namespace netsculpt::io
