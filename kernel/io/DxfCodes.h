#pragma once
// What DXF group codes hold (the DXF reference's group code value types), for DxfScan.

#include <string_view>

namespace netsculpt::io {

/// The application name of netsculpt's extended data (groups 1001/1000) and APPID table entry.
inline constexpr const char* kDxfApplication = "NETSCULPT";

inline bool isRealCode(int c) {
    return (c >= 10 && c <= 59) || (c >= 110 && c <= 149) || (c >= 210 && c <= 239) ||
           (c >= 460 && c <= 469) || (c >= 1010 && c <= 1059);
}

inline bool isIntegerCode(int c) {
    return (c >= 60 && c <= 99) || (c >= 160 && c <= 179) || (c >= 270 && c <= 299) ||
           (c >= 370 && c <= 389) || (c >= 400 && c <= 409) || (c >= 420 && c <= 459) ||
           (c >= 1060 && c <= 1071);
}

/// The counts dxflib allocates its arrays by, wherever the entity is (a BLOCKS or OBJECTS
/// section too): LWPOLYLINE vertices (90), SPLINE knots, control and fit points (72, 73, 74),
/// LEADER vertices (76). Null when `code` is not one of them for `type`.
inline const char* allocatedCount(std::string_view type, int code) {
    if (type == "LWPOLYLINE" && code == 90)
        return "vertex count";
    if (type == "SPLINE" && code == 72)
        return "knot count";
    if (type == "SPLINE" && code == 73)
        return "control point count";
    if (type == "SPLINE" && code == 74)
        return "fit point count";
    if (type == "LEADER" && code == 76)
        return "vertex count";
    return nullptr;
}

inline const char* codeMeaning(int c) {
    switch (c) {
    case 10:
    case 20:
    case 30:
        return "a point coordinate";
    case 11:
    case 21:
    case 31:
        return "a fit point or end point coordinate";
    case 40:
        return "a knot value or radius";
    case 41:
        return "a weight";
    case 42:
        return "a bulge";
    default:
        return "a number";
    }
}

} // namespace netsculpt::io
