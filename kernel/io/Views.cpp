#include "io/Views.h"

#include "model/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace netsculpt::io {

namespace {

constexpr double kAzimuth = -60.0 * std::numbers::pi / 180.0;
constexpr double kElevation = 22.0 * std::numbers::pi / 180.0;
constexpr double kFieldOfView = 35.0 * std::numbers::pi / 180.0;

Vec3 unit(const Vec3& v) {
    return v / v.norm();
}

/// View coordinates (u right, v up) and depth of p, before fitting.
ScreenPoint viewCoordinates(const ViewCamera& cam, const Vec3& p) {
    const Vec3 d = cam.perspective ? p - cam.eye : p;
    ScreenPoint s{d.dot(cam.right), d.dot(cam.up), d.dot(cam.forward)};
    if (cam.perspective) {
        const double depth = std::max(s.depth, 1e-9);
        s.x /= depth;
        s.y /= depth;
    }
    return s;
}

} // namespace

ScreenPoint Panel::project(const Vec3& p) const {
    const ScreenPoint v = viewCoordinates(camera, p);
    return {left + 0.5 * width + (v.x - centreU) * scale,
            top + drawTop + 0.5 * (height - drawTop) - (v.y - centreV) * scale, v.depth};
}

const std::vector<std::string>& viewNames() {
    static const std::vector<std::string> names{"top", "front", "side", "perspective"};
    return names;
}

ViewCamera viewCamera(const std::string& name, const Vec3& lo, const Vec3& hi) {
    ViewCamera cam;
    cam.name = name;
    if (name == "top") {
        cam.right = {1, 0, 0}, cam.up = {0, 1, 0}, cam.forward = {0, 0, -1};
    } else if (name == "front") {
        cam.right = {1, 0, 0}, cam.up = {0, 0, 1}, cam.forward = {0, 1, 0};
    } else if (name == "side") {
        cam.right = {0, 1, 0}, cam.up = {0, 0, 1}, cam.forward = {-1, 0, 0};
    } else if (name == "perspective") {
        const Vec3 toEye{std::cos(kElevation) * std::cos(kAzimuth),
                         std::cos(kElevation) * std::sin(kAzimuth), std::sin(kElevation)};
        cam.perspective = true;
        cam.forward = -toEye;
        cam.right = unit(Vec3{cam.forward.y, -cam.forward.x, 0});
        cam.up = unit(cam.right.cross(cam.forward));
        const Vec3 centre = (lo + hi) * 0.5;
        const double radius = std::max(0.5 * distance(lo, hi), 1e-3);
        cam.eye = centre + toEye * (1.05 * radius / std::sin(0.5 * kFieldOfView));
    } else {
        throw UserError("view must be one of top, front, side, perspective or all; got \"" + name +
                        "\"");
    }
    return cam;
}

std::vector<Panel> layoutSheet(const std::string& view, int width, int height, double titleHeight,
                               double panelTitleHeight, const std::vector<Vec3>& points,
                               const Vec3& lo, const Vec3& hi) {
    std::vector<std::string> names;
    if (view == "all")
        names = viewNames();
    else
        names = {viewCamera(view, lo, hi).name};
    const int columns = names.size() == 1 ? 1 : 2;
    const int rows = names.size() == 1 ? 1 : 2;
    const double cellWidth = double(width) / columns;
    const double cellHeight = (double(height) - titleHeight) / rows;
    std::vector<Panel> panels;
    for (std::size_t i = 0; i < names.size(); ++i) {
        Panel panel;
        panel.camera = viewCamera(names[i], lo, hi);
        panel.left = cellWidth * double(int(i) % columns);
        panel.top = titleHeight + cellHeight * double(int(i) / columns);
        panel.width = cellWidth;
        panel.height = cellHeight;
        panel.drawTop = panelTitleHeight;
        double uMin = std::numeric_limits<double>::infinity(), uMax = -uMin, vMin = uMin,
               vMax = -uMin;
        for (const Vec3& p : points) {
            const ScreenPoint s = viewCoordinates(panel.camera, p);
            uMin = std::min(uMin, s.x), uMax = std::max(uMax, s.x);
            vMin = std::min(vMin, s.y), vMax = std::max(vMax, s.y);
        }
        if (points.empty())
            uMin = uMax = vMin = vMax = 0;
        const double drawHeight = panel.height - panel.drawTop;
        const double margin = 0.07 * std::min(panel.width, drawHeight);
        const double du = uMax - uMin, dv = vMax - vMin;
        const double sx =
            du > 0 ? (panel.width - 2 * margin) / du : std::numeric_limits<double>::infinity();
        const double sy =
            dv > 0 ? (drawHeight - 2 * margin) / dv : std::numeric_limits<double>::infinity();
        panel.scale = std::isfinite(std::min(sx, sy)) ? std::max(std::min(sx, sy), 1e-12) : 1.0;
        panel.centreU = 0.5 * (uMin + uMax);
        panel.centreV = 0.5 * (vMin + vMax);
        panels.push_back(panel);
    }
    return panels;
}

double niceLength(double maxMetres) {
    if (!(maxMetres > 0) || !std::isfinite(maxMetres))
        return 1;
    const double power = std::pow(10.0, std::floor(std::log10(maxMetres)));
    for (double m : {5.0, 2.0, 1.0})
        if (m * power <= maxMetres * (1 + 1e-12))
            return m * power;
    return power;
}

std::string lengthLabel(double metres) {
    const auto text = [](double v, const char* unit) {
        return formatNumber(std::round(v * 1e6) / 1e6) + " " + unit;
    };
    if (metres >= 1000)
        return text(metres / 1000, "km");
    if (metres >= 1)
        return text(metres, "m");
    if (metres >= 0.01)
        return text(metres * 100, "cm");
    return text(metres * 1000, "mm");
}

} // namespace netsculpt::io
