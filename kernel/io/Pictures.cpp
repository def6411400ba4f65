// Pictures: the sheet of views (Canvas.h) written as SVG elements or rasterized to PNG.

#include "io/Canvas.h"
#include "io/Exporters.h"
#include "io/IoText.h"
#include "io/Raster.h"

#include <algorithm>

#include <cmath>
#include <cstdio>

namespace netsculpt::io {

namespace {

/// Drawing coordinates in px rounded to 1/100: shorter files, no visible difference.
std::string px(double value) {
    return numberText(std::round(value * 100) / 100);
}

std::string hex(const Rgb& c) {
    const auto byte = [](double v) { return int(std::lround(std::clamp(v, 0.0, 1.0) * 255)); };
    char text[8];
    std::snprintf(text, sizeof text, "#%02x%02x%02x", byte(c.r), byte(c.g), byte(c.b));
    return text;
}

/// The length of the valid UTF-8 sequence of two to four bytes at text[i] (no overlong form, no
/// surrogate, at most U+10FFFF), 0 if there is none.
std::size_t utf8SequenceAt(const std::string& text, std::size_t i) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned lead = byte(i);
    const std::size_t length = lead >= 0xc2 && lead <= 0xdf   ? 2
                               : lead >= 0xe0 && lead <= 0xef ? 3
                               : lead >= 0xf0 && lead <= 0xf4 ? 4
                                                              : 0;
    if (length == 0 || i + length > text.size())
        return 0;
    for (std::size_t k = 1; k < length; ++k)
        if ((byte(i + k) & 0xc0) != 0x80)
            return 0;
    const unsigned second = byte(i + 1);
    if ((lead == 0xe0 && second < 0xa0) || (lead == 0xed && second > 0x9f) ||
        (lead == 0xf0 && second < 0x90) || (lead == 0xf4 && second > 0x8f))
        return 0;
    return length;
}

/// Text for XML: markup characters escaped; a control character XML forbids, or a byte that is
/// not part of valid UTF-8 (a name set from a script may hold any bytes), written as '?'.
std::string escaped(const std::string& text) {
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        const auto code = static_cast<unsigned char>(c);
        if (code >= 0x80) {
            const std::size_t length = utf8SequenceAt(text, i);
            out += length > 0 ? text.substr(i, length) : "?";
            i += length > 0 ? length - 1 : 0;
            continue;
        }
        if (code < 0x20 && c != '\t' && c != '\n' && c != '\r') {
            out += '?';
            continue;
        }
        switch (c) {
        case '&':
            out += "&amp;";
            break;
        case '<':
            out += "&lt;";
            break;
        case '>':
            out += "&gt;";
            break;
        case '"':
            out += "&quot;";
            break;
        default:
            out += c;
        }
    }
    return out;
}

class SvgCanvas final : public Canvas {
  public:
    std::string body;

    void line(double x0, double y0, double x1, double y1, const Rgb& colour,
              double width) override {
        if (!(std::isfinite(x0) && std::isfinite(y0) && std::isfinite(x1) && std::isfinite(y1)))
            return;
        body += "<line x1=\"" + px(x0) + "\" y1=\"" + px(y0) + "\" x2=\"" + px(x1) + "\" y2=\"" +
                px(y1) + "\" stroke=\"" + hex(colour) + "\" stroke-width=\"" + px(width) + "\"/>\n";
    }
    void rect(double x, double y, double w, double h, const Rgb& colour) override {
        body += "<rect x=\"" + px(x) + "\" y=\"" + px(y) + "\" width=\"" + px(w) + "\" height=\"" +
                px(h) + "\" fill=\"" + hex(colour) + "\"/>\n";
    }
    void disc(double x, double y, double radius, const Rgb& colour) override {
        body += "<circle cx=\"" + px(x) + "\" cy=\"" + px(y) + "\" r=\"" + px(radius) +
                "\" fill=\"" + hex(colour) + "\"/>\n";
    }
    void text(double x, double y, const std::string& text, double scale,
              const Rgb& colour) override {
        body += "<text x=\"" + px(x) + "\" y=\"" + px(y + 7 * scale) + "\" font-size=\"" +
                px(9.5 * scale) + "\" fill=\"" + hex(colour) + "\">" + escaped(text) + "</text>\n";
    }
    double textWidth(const std::string& text, double scale) const override {
        return 5.4 * scale * double(text.size()); // about the width of the sans-serif at 9.5 px
    }
    void beginGroup(const std::string& id) override { body += "<g id=\"" + escaped(id) + "\">\n"; }
    void endGroup() override { body += "</g>\n"; }
};

} // namespace

std::string svgText(const ExportInput& in) {
    const ExportOptions& o = in.options;
    const Scene scene = buildScene(in.sculpture, in.compiled, o.colourBy, in.status.relaxed);
    const Sheet sheet = layoutFor(scene, o.view, o.width, o.height);
    SvgCanvas canvas;
    drawSheet(canvas, scene, sheet, o.width, o.height);
    const std::string w = std::to_string(o.width), h = std::to_string(o.height);
    return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
           "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" +
           w + "\" height=\"" + h + "\" viewBox=\"0 0 " + w + " " + h +
           "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" "
           "stroke-linecap=\"round\">\n" +
           "<title>" + escaped(scene.title) + "</title>\n" + canvas.body + "</svg>\n";
}

std::string pngBytes(const ExportInput& in) {
    const ExportOptions& o = in.options;
    const Scene scene = buildScene(in.sculpture, in.compiled, o.colourBy, in.status.relaxed);
    const Sheet sheet = layoutFor(scene, o.view, o.width, o.height);
    RasterCanvas canvas(o.width, o.height);
    drawSheet(canvas, scene, sheet, o.width, o.height);
    return encodePng(canvas.rgb8(), o.width, o.height);
}

} // namespace netsculpt::io
