#pragma once
// A 2D drawing surface in pixels (x right, y down) that the sheet of views is drawn on: the PNG
// rasterizer and the SVG writer implement it, so both pictures come from one drawing routine.

#include "io/Scene.h"
#include "io/Views.h"

#include <string>
#include <vector>

namespace netsculpt::io {

class Canvas {
  public:
    virtual ~Canvas() = default;
    /// A straight stroke with round caps, `width` px wide.
    virtual void line(double x0, double y0, double x1, double y1, const Rgb& colour,
                      double width) = 0;
    /// A filled axis-aligned rectangle.
    virtual void rect(double x, double y, double w, double h, const Rgb& colour) = 0;
    /// A filled disc.
    virtual void disc(double x, double y, double radius, const Rgb& colour) = 0;
    /// Text whose top-left corner is (x, y); `scale` 1 = glyphs about 7 px tall.
    virtual void text(double x, double y, const std::string& text, double scale,
                      const Rgb& colour) = 0;
    /// The width of `text` in px at `scale`.
    virtual double textWidth(const std::string& text, double scale) const = 0;
    /// Groups what follows (an SVG <g id=...>); no effect on a raster.
    virtual void beginGroup(const std::string& /*id*/) {}
    virtual void endGroup() {}
};

/// The layout of a sheet for a canvas of width x height px: text scale and the panels.
struct Sheet {
    double textScale = 1;
    double titleHeight = 0;
    std::vector<Panel> panels;
};
Sheet layoutFor(const Scene& scene, const std::string& view, int width, int height);

/// Draws the whole sheet: background, title and legend, then per panel its title, the bars and
/// rails back to front, the held knots, and a scale bar (orthographic views).
void drawSheet(Canvas& canvas, const Scene& scene, const Sheet& sheet, int width, int height);

} // namespace netsculpt::io
