#pragma once
// Our own anti-aliased rasterizer for the PNG pictures: strokes and discs by exact distance
// coverage (a 1-px linear falloff at the edge), rectangles by box-filtered area, text from
// stb_easy_font's glyph quads. Colours blend in sRGB.

#include "io/Canvas.h"

#include <cstdint>
#include <string>
#include <vector>

namespace netsculpt::io {

class RasterCanvas final : public Canvas {
  public:
    RasterCanvas(int width, int height);

    void line(double x0, double y0, double x1, double y1, const Rgb& colour, double width) override;
    void rect(double x, double y, double w, double h, const Rgb& colour) override;
    void disc(double x, double y, double radius, const Rgb& colour) override;
    void text(double x, double y, const std::string& text, double scale,
              const Rgb& colour) override;
    double textWidth(const std::string& text, double scale) const override;

    int width() const { return width_; }
    int height() const { return height_; }
    /// 8-bit RGB, row by row from the top.
    std::vector<std::uint8_t> rgb8() const;

  private:
    int width_, height_;
    std::vector<float> pixels_; // RGB, sRGB in [0, 1]

    void blend(int x, int y, const Rgb& colour, double alpha);
};

/// PNG bytes of an 8-bit RGB image (stb_image_write).
std::string encodePng(const std::vector<std::uint8_t>& rgb, int width, int height);

} // namespace netsculpt::io
