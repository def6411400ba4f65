#pragma once
// Block references (INSERT) read through their transform: every rail-making entity of model
// space, and of every block inserted there (nested inserts too), placed in world coordinates.

#include "io/DxfCollector.h"

#include <string>
#include <vector>

namespace netsculpt::io {

/// An affine map x -> linear * x + offset, the linear part by its columns.
struct Affine {
    Vec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
    Vec3 offset;
    Vec3 linear(const Vec3& p) const { return x * p.x + y * p.y + z * p.z; }
    Vec3 operator()(const Vec3& p) const { return linear(p) + offset; }
    /// This map after `inner`: p -> (*this)(inner(p)).
    Affine after(const Affine& inner) const {
        return {linear(inner.x), linear(inner.y), linear(inner.z), (*this)(inner.offset)};
    }
};

/// The map from a block's coordinates to the coordinates the INSERT is drawn in:
/// OCS(extrusion) * (rotation about z * scale * (p - base) + insertion point). The DXF reference
/// (and ezdxf's Insert.matrix44) define it so.
Affine insertTransform(const DxfInsert& insert, const Vec3& base);

/// At most this many points (a LINE 2, an ARC its samples, a SPLINE its control points) are
/// placed through block references, nested ones included: a block inserted ten times in a block
/// inserted ten times, six deep, makes a 2.5 KB file a million rails.
inline constexpr std::size_t kMaxInsertedPoints = 1'000'000;
/// At most this many block references are placed inside blocks: sixteen levels of blocks that
/// each insert the next one ten times place no point but 10^16 references.
inline constexpr std::size_t kMaxInsertedReferences = 1'000'000;

/// Where an entity ends up.
struct Placed {
    const DxfEntity* entity = nullptr;
    std::string layer; ///< its own, or for an entity on layer 0 in a block the INSERT's
    std::vector<std::string> insertLayers; ///< the layers of the INSERTs it is drawn through
    std::string name;  ///< the rail's name: LAYER:HANDLE; INSLAYER:INSHANDLE/BLOCK:HANDLE inside
    std::string where; ///< for messages: the entity, then each INSERT it is drawn through
    std::string group; ///< LINEs and ARCs chain within one group: one per block reference
    std::size_t order = 0; ///< the line of the model-space entity (the outermost INSERT)
};

struct PlacedDrawing {
    std::vector<std::pair<Placed, CurveSpec>> curves;
    std::vector<std::pair<Placed, std::vector<Vec3>>> parts;
    std::vector<std::pair<Placed, DxfSpline>> splines;
    /// Entities that cannot be rails, with the reason (DxfContent::refusals), placed like the
    /// others: the importer refuses the first one whose layer is read.
    std::vector<std::pair<Placed, std::string>> refusals;
};

/// Model space with every INSERT replaced by its block's content, transformed. UserError naming
/// the INSERT and the block (and asking to explode it in the CAD program) for a block that is
/// not defined, contains itself, is nested deeper than 16, an array (MINSERT) or inserted with
/// a scale of 0; and naming the INSERT of model space, its block and the count when the
/// drawing's INSERTs would place more than kMaxInsertedPoints points or kMaxInsertedReferences
/// block references (counted before anything is placed). Entities that cannot be rails are
/// placed into `refusals`, not refused here.
PlacedDrawing placeDrawing(const std::string& file, const DxfDrawing& drawing);

} // namespace netsculpt::io
