#include "io/DxfBlocks.h"

#include "io/IoText.h"
#include "model/Error.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace netsculpt::io {

namespace {

constexpr int kMaxNesting = 16;
/// Counts of inserted points stop here (sums of capped counts cannot overflow).
constexpr std::size_t kCountCap = std::size_t(1) << 60;

/// What an INSERT places: points (a LINE 2, an ARC its samples, ...) and the block references
/// nested in its block.
struct Inserted {
    std::size_t points = 0, references = 0;
};

/// How the entities of one content are placed.
struct Placement {
    Affine toWorld;
    std::string namePrefix; ///< "" in model space; "INS:31/RING:" in a block
    std::string via;        ///< "" in model space; ", inserted by INSERT 31 on layer INS ..."
    std::string layer;      ///< the layer entities on layer 0 take; "" in model space
    std::vector<std::string> insertLayers;
    std::vector<std::string> blocks; ///< the blocks it is inside, outermost first
    std::string group;
    std::size_t order = 0; ///< 0 in model space: each entity's own line
};

class Placer {
  public:
    Placer(const std::string& file, const DxfDrawing& drawing) : file_(file), drawing_(drawing) {}

    PlacedDrawing out;

    /// Refuses the first INSERT of model space past which the drawing's INSERTs place more than
    /// kMaxInsertedPoints points or kMaxInsertedReferences block references.
    void checkBudget() {
        Inserted total;
        for (const DxfInsert& insert : drawing_.model.inserts) {
            const Inserted placed = inserted(insert);
            total.points = std::min(total.points + placed.points, kCountCap);
            total.references = std::min(total.references + placed.references, kCountCap);
            if (total.points > kMaxInsertedPoints)
                overBudget(insert, placed.points, total.points, kMaxInsertedPoints, "points");
            if (total.references > kMaxInsertedReferences)
                overBudget(insert, placed.references, total.references, kMaxInsertedReferences,
                           "block references");
        }
    }

    void place(const DxfContent& content, const Placement& at) {
        for (const auto& [e, reason] : content.refusals)
            out.refusals.push_back({placed(*e, at), reason});
        for (const auto& [e, spec] : content.curves) {
            CurveSpec moved = spec;
            for (Vec3& p : moved.points)
                p = at.toWorld(p);
            out.curves.push_back({placed(*e, at), std::move(moved)});
        }
        for (const auto& [e, points] : content.parts) {
            std::vector<Vec3> moved = points;
            for (Vec3& p : moved)
                p = at.toWorld(p);
            out.parts.push_back({placed(*e, at), std::move(moved)});
        }
        for (const DxfSpline& s : content.splines) {
            DxfSpline moved = s; // B-splines are affine invariant: their control points move
            for (Vec3& p : moved.control)
                p = at.toWorld(p);
            out.splines.push_back({placed(*s.entity, at), std::move(moved)});
        }
        for (const DxfInsert& insert : content.inserts)
            placeInsert(insert, at);
    }

  private:
    const std::string& file_;
    const DxfDrawing& drawing_;
    std::map<const DxfContent*, Inserted> placed_; ///< what a block places, nested ones included
    std::set<const DxfContent*> counting_;

    [[noreturn]] void overBudget(const DxfInsert& insert, std::size_t placed, std::size_t total,
                                 std::size_t most, const std::string& what) const {
        const std::string count =
            placed >= kCountCap ? "more than " + std::to_string(kCountCap) : std::to_string(placed);
        throw UserError(file_ + ": " + insert.entity->describe() + ": places " + count + " " +
                        what + " through block " + quoted(insert.block, 80) +
                        " (the block references inside it included)" +
                        (total > placed ? ", " + std::to_string(total - placed) +
                                              " more through the INSERTs before it"
                                        : std::string()) +
                        "; netsculpt places at most " + std::to_string(most) + " " + what +
                        " through block references: insert fewer copies, or put the rails in a "
                        "drawing of their own");
    }

    /// What an INSERT places, each count at most kCountCap. An undefined block, or one inside
    /// itself, places nothing here: placing it is refused.
    Inserted inserted(const DxfInsert& insert) {
        const auto found = drawing_.blocks.find(insert.block);
        if (found == drawing_.blocks.end())
            return {};
        const DxfContent* block = &found->second;
        if (const auto known = placed_.find(block); known != placed_.end())
            return known->second;
        if (!counting_.insert(block).second)
            return {};
        Inserted n{block->refusals.size(), 0};
        const auto add = [](std::size_t& count, std::size_t more) {
            count = std::min(count + more, kCountCap);
        };
        for (const auto& curve : block->curves)
            add(n.points, curve.second.points.size());
        for (const auto& part : block->parts)
            add(n.points, part.second.size());
        for (const DxfSpline& s : block->splines)
            add(n.points, s.control.size());
        for (const DxfInsert& inner : block->inserts) {
            const Inserted more = inserted(inner);
            add(n.points, more.points);
            add(n.references, more.references);
            add(n.references, 1);
        }
        counting_.erase(block);
        placed_[block] = n;
        return n;
    }

    static std::string layerIn(const std::string& own, const Placement& at) {
        return own == "0" && !at.layer.empty() ? at.layer : own;
    }

    static Placed placed(const DxfEntity& e, const Placement& at) {
        Placed p;
        p.entity = &e;
        p.layer = layerIn(e.layer, at);
        p.insertLayers = at.insertLayers;
        p.name = at.namePrefix.empty() ? e.railName() : at.namePrefix + e.handleOrIndex();
        p.where = e.describe() + at.via;
        p.group = at.group;
        p.order = at.order != 0 ? at.order : e.line;
        return p;
    }

    [[noreturn]] void refuse(const DxfInsert& insert, const Placement& at,
                             const std::string& what) const {
        throw UserError(file_ + ": " + insert.entity->describe() + at.via + ": " + what +
                        "; explode the block reference in the CAD program (EXPLODE) and export "
                        "the DXF again");
    }

    void placeInsert(const DxfInsert& insert, const Placement& at) {
        const DxfEntity& e = *insert.entity;
        const std::string block = quoted(insert.block, 80);
        const auto found = drawing_.blocks.find(insert.block);
        if (found == drawing_.blocks.end() || !found->second.defined)
            refuse(insert, at, "refers to block " + block + ", which the file does not define");
        if (std::find(at.blocks.begin(), at.blocks.end(), insert.block) != at.blocks.end())
            refuse(insert, at, "inserts block " + block + " inside itself");
        if (int(at.blocks.size()) >= kMaxNesting)
            refuse(insert, at, "nests block " + block + " " + std::to_string(at.blocks.size() + 1) +
                                   " deep; netsculpt reads block references nested up to " +
                                   std::to_string(kMaxNesting) + " deep");
        if (insert.columns != 1 || insert.rows != 1)
            refuse(insert, at,
                   "is an array of " + std::to_string(insert.columns) + " columns by " +
                       std::to_string(insert.rows) + " rows of block " + block +
                       " (a MINSERT); netsculpt does not read block arrays");
        const Vec3 s = insert.scale;
        if (s.x == 0 || s.y == 0 || s.z == 0)
            refuse(insert, at,
                   "inserts block " + block + " with a scale of 0 (x " + numberText(s.x) + ", y " +
                       numberText(s.y) + ", z " + numberText(s.z) +
                       "); a rail cannot be flattened to nothing");
        Placement inner;
        inner.toWorld = at.toWorld.after(insertTransform(insert, found->second.base));
        inner.layer = layerIn(e.layer, at);
        inner.namePrefix =
            (at.namePrefix.empty() ? e.railName() : at.namePrefix + e.handleOrIndex()) + "/" +
            insert.block + ":";
        // A scale other than 1 is named: a tiny one can shrink a rail to a point.
        const std::string scaled = s == Vec3{1, 1, 1}
                                       ? std::string()
                                       : " with a scale of x " + numberText(s.x) + ", y " +
                                             numberText(s.y) + ", z " + numberText(s.z);
        inner.via = ", inserted by " + e.describe() + scaled + at.via;
        inner.insertLayers = at.insertLayers;
        inner.insertLayers.push_back(inner.layer);
        inner.blocks = at.blocks;
        inner.blocks.push_back(insert.block);
        inner.group = at.group + std::to_string(e.line) + "/";
        inner.order = at.order != 0 ? at.order : e.line;
        place(found->second, inner);
    }
};

} // namespace

Affine insertTransform(const DxfInsert& insert, const Vec3& base) {
    const double angle = std::fmod(insert.degrees, 360.0) * (3.14159265358979323846 / 180.0);
    const double c = std::cos(angle), s = std::sin(angle);
    const Vec3 k = insert.scale;
    Affine a;
    a.x = insert.ocs.toWorld({k.x * c, k.x * s, 0});
    a.y = insert.ocs.toWorld({-k.y * s, k.y * c, 0});
    a.z = insert.ocs.toWorld({0, 0, k.z});
    a.offset = insert.ocs.toWorld(insert.at) - a.linear(base);
    return a;
}

PlacedDrawing placeDrawing(const std::string& file, const DxfDrawing& drawing) {
    Placer placer(file, drawing);
    placer.checkBudget();
    placer.place(drawing.model, Placement{});
    return std::move(placer.out);
}

} // namespace netsculpt::io
