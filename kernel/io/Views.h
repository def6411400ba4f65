#pragma once
// The views of the pictures (svg, png) and where they sit on the sheet. Pixel coordinates: x to
// the right, y down, origin at the image's top-left corner, pixel centres at +0.5.
//
//   top          looking down (-z): right = +x, up = +y
//   front        looking along +y:  right = +x, up = +z
//   side         looking along -x:  right = +y, up = +z
//   perspective  from the front right, above (azimuth -60 deg, elevation 22 deg), 35 deg field
//                of view, at a distance that shows the whole sculpture

#include "geometry/Vec3.h"

#include <string>
#include <vector>

namespace netsculpt::io {

struct ViewCamera {
    std::string name;
    bool perspective = false;
    Vec3 right, up, forward; ///< unit vectors; forward points away from the viewer
    Vec3 eye;                ///< perspective only
};

/// A point on the screen: pixel coordinates and depth (larger = farther from the viewer).
struct ScreenPoint {
    double x = 0, y = 0, depth = 0;
};

/// One view fitted into a rectangle of the sheet.
struct Panel {
    ViewCamera camera;
    double left = 0, top = 0, width = 0, height = 0; ///< the panel's rectangle, px
    double scale = 1;                                ///< px per view unit (ortho: px per metre)
    double centreU = 0, centreV = 0; ///< view coordinates drawn at the drawing area's centre
    double drawTop = 0; ///< px from the panel's top where its drawing area starts (below its title)

    ScreenPoint project(const Vec3& p) const;
};

/// The view names in sheet order: top, front, side, perspective.
const std::vector<std::string>& viewNames();

/// The camera of a named view for a scene within the box [lo, hi]; UserError listing the
/// names (and "all") for an unknown one.
ViewCamera viewCamera(const std::string& name, const Vec3& lo, const Vec3& hi);

/// The sheet: a title bar of `titleHeight` px across the top, then one panel (a single view)
/// or a 2x2 grid (view "all"), each fitted so that `points` fill it with a margin.
std::vector<Panel> layoutSheet(const std::string& view, int width, int height, double titleHeight,
                               double panelTitleHeight, const std::vector<Vec3>& points,
                               const Vec3& lo, const Vec3& hi);

/// A round length for a scale bar no longer than `maxMetres`: 1, 2 or 5 times a power of ten.
double niceLength(double maxMetres);
/// "2 m", "50 cm", "5 mm", "1 km".
std::string lengthLabel(double metres);

} // namespace netsculpt::io
