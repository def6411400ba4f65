#pragma once
// A syntax pass over an ASCII DXF file before dxflib reads it. dxflib is lenient by design: it
// reads a malformed number as 0, pads or drops knots and vertices whose count disagrees with the
// declared one, and says nothing about a truncated file. This pass finds those problems first,
// with the line number, and records per entity what dxflib does not tell (the handle as
// written, the line, how many values of each group code it holds).

#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace netsculpt::io {

struct DxfEntity {
    std::string type;        ///< "LINE", "SPLINE", ...
    std::size_t line = 0;    ///< line number of the entity's "0" group code (1-based)
    std::string handle;      ///< group 5 as written; empty when the file has none
    std::string layer = "0"; ///< group 8
    bool paperSpace = false; ///< group 67 = 1
    std::string block;       ///< the block definition holding it; empty in the ENTITIES section
    std::size_t index = 0;   ///< position among the ENTITIES, or in its block (0-based)
    /// How many groups of code c (< 100) the entity holds: 10 = control points / vertices,
    /// 40 = knots, 41 = weights, 11 = fit points.
    std::array<int, 100> count{};
    /// The strings (group 1000) of its extended data of application NETSCULPT, as written:
    /// {"rail", NAME} on a rail netsculpt wrote, {"bar"} on a bar (DxfExport.h).
    std::vector<std::string> netsculptMark;
    /// The first integer value of codes 60..99 (e.g. 72 = declared knot count); -1 = absent.
    std::array<long long, 40> integer;

    DxfEntity() { integer.fill(-1); }
    long long declared(int code) const { return integer[std::size_t(code - 60)]; }
    /// "SPLINE 2F on layer RAILS (line 2074)" — for messages ("... in block RING" in a block).
    std::string describe() const;
    /// "2F", or "#N" (N = index + 1) when the file has no handles.
    std::string handleOrIndex() const;
    /// "RAILS:2F", or "RAILS:#N" when the file has no handles; the name in netsculpt's mark
    /// when the entity carries one.
    std::string railName() const;
    /// A bar of a net netsculpt wrote (its mark says "bar"): not a rail.
    bool netsculptBar() const;
};

/// An entry of the LAYER table.
struct DxfLayer {
    std::string name;
    int flags = 0;        ///< group 70: 1 = frozen
    long long colour = 7; ///< group 62: negative = the layer is off
    bool frozen() const { return flags & 1; }
    bool off() const { return colour < 0; }
};

struct DxfScan {
    std::vector<DxfEntity> entities; ///< the ENTITIES section, then blocks' entities; file order
    std::vector<DxfLayer> layers;    ///< the LAYER table
    std::map<std::size_t, std::size_t> byLine; ///< start line -> index into entities
    std::size_t lines = 0;
    const DxfEntity* at(std::size_t line) const {
        auto it = byLine.find(line);
        return it == byLine.end() ? nullptr : &entities[it->second];
    }
};

/// Checks `text` (the whole file, decoded to UTF-8 by decodeDxfText) and returns what it
/// recorded. Throws UserError "<file>: line N: <reason>" for: binary data, a group code that is
/// not an integer, a number that does not parse or is not finite (in ENTITIES), a line longer
/// than dxflib reads, a missing ENDSEC/EOF (truncated file), counts that are negative or
/// disagree with the values present (SPLINE 72/73/41, LWPOLYLINE 90).
DxfScan scanDxf(const std::string& file, const std::string& text);

} // namespace netsculpt::io
