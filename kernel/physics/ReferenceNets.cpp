#include "physics/ReferenceNets.h"

#include "model/Error.h"

#include <cmath>
#include <numbers>
#include <string>

namespace netsculpt {

namespace {

void checkMaterial(const NetMaterial& material) {
    auto positive = [](double v) { return std::isfinite(v) && v > 0; };
    if (!positive(material.stiffness))
        throw UserError("stiffness must be > 0 N, got " + formatNumber(material.stiffness));
    if (!std::isfinite(material.compressionRatio) || material.compressionRatio < 0)
        throw UserError("compression_ratio must be >= 0, got " +
                        formatNumber(material.compressionRatio));
    if (!positive(material.knotMass))
        throw UserError("knot_mass must be > 0 kg, got " + formatNumber(material.knotMass));
    if (!std::isfinite(material.linearDensity) || material.linearDensity < 0)
        throw UserError("linear_density must be >= 0 kg/m, got " +
                        formatNumber(material.linearDensity));
}

/// Builds a system knot by knot and bar by bar; finish() sets the masses.
class Builder {
  public:
    explicit Builder(const NetMaterial& material) : material_(material) { checkMaterial(material); }

    std::uint32_t addKnot(const Vec3& position, int row, int column, RailHold hold = {}) {
        system_.position.push_back(position);
        system_.fixed.push_back(hold.rail ? 1 : 0);
        system_.hold.push_back(hold);
        system_.refStart.push_back(static_cast<std::uint32_t>(system_.refs.size()));
        system_.refs.push_back(KnotRef{PieceId(1), row, column});
        return static_cast<std::uint32_t>(system_.position.size() - 1);
    }

    void addBar(std::uint32_t a, std::uint32_t b, double restLength) {
        const double kTension = material_.stiffness / restLength;
        system_.barA.push_back(a);
        system_.barB.push_back(b);
        system_.restLength.push_back(restLength);
        system_.kTension.push_back(kTension);
        system_.kCompression.push_back(material_.compressionRatio * kTension);
        system_.linearDensity.push_back(material_.linearDensity);
        system_.barPiece.push_back(PieceId(1));
    }

    MassSpringSystem finish() {
        system_.refStart.push_back(static_cast<std::uint32_t>(system_.refs.size()));
        system_.mass.assign(system_.position.size(), material_.knotMass);
        for (std::size_t b = 0; b < system_.barCount(); ++b) {
            const double half = 0.5 * material_.linearDensity * system_.restLength[b];
            system_.mass[system_.barA[b]] += half;
            system_.mass[system_.barB[b]] += half;
        }
        return std::move(system_);
    }

  private:
    NetMaterial material_;
    MassSpringSystem system_;
};

void checkGrid(int rows, int columns, int minColumns, double barLength) {
    if (rows < 2)
        throw UserError("rows must be >= 2, got " + std::to_string(rows));
    if (columns < minColumns)
        throw UserError("columns must be >= " + std::to_string(minColumns) + ", got " +
                        std::to_string(columns));
    if (!std::isfinite(barLength) || barLength <= 0)
        throw UserError("bar length must be > 0 m, got " + formatNumber(barLength));
}

/// Eq. 2: the drop h below the parents' midpoint for a bar l under parents s apart.
double dropBelowParents(double barLength, double parentSpacing) {
    if (barLength <= parentSpacing / 2)
        throw UserError("bar length " + formatNumber(barLength) +
                        " m is not longer than half the knot spacing " +
                        formatNumber(parentSpacing) + " m, so a knot cannot hang below two");
    return std::sqrt(barLength * barLength - parentSpacing * parentSpacing / 4);
}

/// Rows 1..rows-1 of a staggered piece below row 0 (knot index = row * columns + column):
/// odd rows hang from (r-1, c), (r-1, c+1); even rows from (r-1, c-1), (r-1, c). Positions by
/// Eq. 1, 2; in an open piece a knot with one parent starts half the row spacing beside it.
void addRows(Builder& builder, std::vector<Vec3>& positions, int rows, int columns, bool closed,
             double barLength, double openSpacing) {
    auto index = [columns](int r, int c) { return static_cast<std::uint32_t>(r * columns + c); };
    for (int r = 1; r < rows; ++r) {
        for (int c = 0; c < columns; ++c) {
            int first = r % 2 ? c : c - 1, second = r % 2 ? c + 1 : c;
            if (closed) {
                first = (first + columns) % columns;
                second = second % columns;
            }
            const bool hasFirst = first >= 0, hasSecond = second < columns;
            Vec3 mid;
            double spacing = openSpacing;
            if (hasFirst && hasSecond) {
                const Vec3 a = positions[index(r - 1, first)], b = positions[index(r - 1, second)];
                mid = (a + b) * 0.5;
                spacing = distance(a, b);
            } else if (hasFirst) {
                mid = positions[index(r - 1, first)] + Vec3{openSpacing / 2, 0, 0};
            } else {
                mid = positions[index(r - 1, second)] - Vec3{openSpacing / 2, 0, 0};
            }
            positions.push_back(mid - Vec3{0, 0, dropBelowParents(barLength, spacing)});
        }
    }
    // Knots first (so that indices are row * columns + column), then the bars.
    for (int r = 1; r < rows; ++r)
        for (int c = 0; c < columns; ++c)
            builder.addKnot(positions[index(r, c)], r, c);
    for (int r = 1; r < rows; ++r) {
        for (int c = 0; c < columns; ++c) {
            int first = r % 2 ? c : c - 1, second = r % 2 ? c + 1 : c;
            if (closed) {
                first = (first + columns) % columns;
                second = second % columns;
            }
            if (first >= 0)
                builder.addBar(index(r - 1, first), index(r, c), barLength);
            if (second < columns)
                builder.addBar(index(r - 1, second), index(r, c), barLength);
        }
    }
}

} // namespace

MassSpringSystem makeChain(const Vec3& from, const Vec3& to, int links, double barLength,
                           const NetMaterial& material, double sag) {
    if (links < 1)
        throw UserError("a chain needs >= 1 link, got " + std::to_string(links));
    checkGrid(2, 1, 1, barLength);
    Builder builder(material);
    for (int i = 0; i <= links; ++i) {
        const double t = static_cast<double>(i) / links;
        const Vec3 p = from + (to - from) * t - Vec3{0, 0, 4 * sag * t * (1 - t)};
        const bool end = i == 0 || i == links;
        builder.addKnot(p, 0, i, end ? RailHold{RailId(i == 0 ? 1 : 2), 0} : RailHold{});
    }
    for (int i = 0; i < links; ++i)
        builder.addBar(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i + 1), barLength);
    return builder.finish();
}

MassSpringSystem makeSheet(const SheetSpec& spec) {
    checkGrid(spec.rows, spec.columns, 2, spec.barLength);
    if (!std::isfinite(spec.spacing) || spec.spacing <= 0)
        throw UserError("spacing must be > 0 m, got " + formatNumber(spec.spacing));
    Builder builder(spec.material);
    std::vector<Vec3> positions;
    for (int c = 0; c < spec.columns; ++c) {
        positions.push_back({c * spec.spacing, 0, 0});
        builder.addKnot(positions.back(), 0, c,
                        RailHold{RailId(1), static_cast<double>(c) / (spec.columns - 1)});
    }
    addRows(builder, positions, spec.rows, spec.columns, false, spec.barLength, spec.spacing);
    MassSpringSystem system = builder.finish();
    if (spec.bottomRailOffset) {
        const std::size_t last = static_cast<std::size_t>((spec.rows - 1) * spec.columns);
        for (int c = 0; c < spec.columns; ++c) {
            const std::size_t j = last + static_cast<std::size_t>(c);
            system.position[j] = Vec3{system.position[j].x, 0, 0} + *spec.bottomRailOffset;
            system.fixed[j] = 1;
            system.hold[j] = RailHold{RailId(2), static_cast<double>(c) / (spec.columns - 1)};
        }
    }
    return system;
}

MassSpringSystem makeTube(const TubeSpec& spec) {
    checkGrid(spec.rows, spec.columns, 3, spec.barLength);
    if (!std::isfinite(spec.radius) || spec.radius <= 0)
        throw UserError("radius must be > 0 m, got " + formatNumber(spec.radius));
    Builder builder(spec.material);
    std::vector<Vec3> positions;
    for (int c = 0; c < spec.columns; ++c) {
        const double t = static_cast<double>(c) / spec.columns;
        const double angle = 2 * std::numbers::pi * t;
        positions.push_back({spec.radius * std::cos(angle), spec.radius * std::sin(angle), 0});
        builder.addKnot(positions.back(), 0, c, RailHold{RailId(1), t});
    }
    addRows(builder, positions, spec.rows, spec.columns, true, spec.barLength, 0);
    return builder.finish();
}

} // namespace netsculpt
