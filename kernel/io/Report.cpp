// The fabrication and load report (Report.h): counts, lengths and masses per piece, reactions
// per rail point, and the sculpture's totals with the force balance check.

#include "io/Report.h"

#include "io/ReportSections.h"
#include "io/Scene.h"
#include "physics/Forces.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <optional>

namespace netsculpt {

namespace {

using nlohmann::json;

json vec(const Vec3& v) {
    return {{"x", v.x}, {"y", v.y}, {"z", v.z}};
}

/// The (piece, row, column) knot k stands for, preferring `piece` when it holds the knot.
KnotRef refOf(const MassSpringSystem& sys, std::uint32_t k, PieceId piece) {
    for (std::uint32_t i = sys.refStart[k]; i < sys.refStart[k + 1]; ++i)
        if (sys.refs[i].piece == piece)
            return sys.refs[i];
    return sys.refs[sys.refStart[k]];
}

/// Where bar b is: its index, its piece and its two knots' (row, column) in that piece.
json barAt(const MassSpringSystem& sys, std::size_t b) {
    const PieceId piece = sys.barPiece[b];
    const KnotRef a = refOf(sys, sys.barA[b], piece), e = refOf(sys, sys.barB[b], piece);
    return {{"bar", b},
            {"piece", piece.value},
            {"a", {{"row", a.row}, {"column", a.column}}},
            {"b", {{"row", e.row}, {"column", e.column}}}};
}

/// A rail edge as stored (at, step, offset: DESIGN.md "Pieces") and where its column 0 is: the
/// rail position `start` and the distance along the rail to it, `start_along`, in metres.
json railEdge(const Sculpture& s, const RailEdge& e) {
    const Curve& curve = s.rail(e.rail).curve();
    const double start = curve.normalizedPosition(railPosition(e, 0));
    return {{"kind", "rail"},
            {"rail", e.rail.value},
            {"rail_name", s.rail(e.rail).name},
            {"at", e.at},
            {"step", e.step},
            {"offset", e.offset},
            {"reverse", e.reverse},
            {"start", start},
            {"start_along", curve.distanceAlong(start)}};
}

/// The parents' last rows as the child hangs from them, numbered as one row (sourceRow): each
/// part's run of knots {piece, row, first_column, last_column, first_knot}. A seam knot is in
/// the run before it when both parts end on the same row, else it is two knots, one in each.
json joinedRow(const std::vector<KnotKey>& row) {
    json runs = json::array();
    for (std::size_t i = 0; i < row.size(); ++i) {
        const KnotKey& k = row[i];
        if (runs.empty() || runs.back()["piece"] != k.piece.value || runs.back()["row"] != k.row)
            runs.push_back({{"piece", k.piece.value},
                            {"row", k.row},
                            {"first_column", k.column},
                            {"first_knot", i}});
        runs.back()["last_column"] = k.column;
    }
    return runs;
}

json pieceTop(const Sculpture& s, const Piece& p) {
    if (p.onRail())
        return railEdge(s, p.railTop());
    const ParentEdge& e = p.parentTop();
    json parents = json::array();
    for (PieceId id : e.parents)
        parents.push_back(id.value);
    const std::vector<KnotKey> row = sourceRow(s, e);
    return {{"kind", "piece"},
            {"parents", parents},
            {"gear", toString(e.gear)},
            {"gear_value", e.gear.value()},
            {"offset", e.offset},
            {"ring", e.ringClosed},
            {"joined_knots", row.size()},
            {"joined_row", joinedRow(row)}};
}

/// (l - l_eq) / l_eq of bar b at the system's positions.
double barStrain(const MassSpringSystem& sys, std::size_t b) {
    return distance(sys.position[sys.barA[b]], sys.position[sys.barB[b]]) / sys.restLength[b] - 1;
}

/// Whether knot k is in `column` of `piece`.
bool inColumn(const MassSpringSystem& sys, std::uint32_t k, PieceId piece, int column) {
    for (std::uint32_t i = sys.refStart[k]; i < sys.refStart[k + 1]; ++i)
        if (sys.refs[i].piece == piece && sys.refs[i].column == column)
            return true;
    return false;
}

/// Seam `seam` seen from `p`, the other piece on `side`. The bars along the seam column (left's
/// last column, right's column 0) are in both pieces and made once, counted in the piece that
/// owns them.
json seamReport(const Sculpture& s, const MassSpringSystem& sys, const Seam& seam, PieceId p) {
    const int column = s.pieces.at(seam.left).columns - 1;
    const auto onSeam = [&](std::uint32_t k) {
        return inColumn(sys, k, seam.left, column) && inColumn(sys, k, seam.right, 0);
    };
    std::size_t shared = 0;
    PieceId owner = seam.left;
    for (std::size_t b = 0; b < sys.barCount(); ++b)
        if (onSeam(sys.barA[b]) && onSeam(sys.barB[b])) {
            ++shared;
            owner = sys.barPiece[b];
        }
    const bool left = seam.right == p;
    const int rows = std::min(s.pieces.at(seam.left).rows, s.pieces.at(seam.right).rows);
    return {{"side", left ? "left" : "right"},
            {"piece", (left ? seam.left : seam.right).value},
            {"column", left ? 0 : column},
            {"other_column", left ? column : 0},
            {"rows", rows},
            {"shared_bars", shared},
            {"shared_bars_counted_in", owner.value}};
}

/// The bar lengths of `p` as they are knotted when its length varies by row: the bars between
/// rows r and r + 1 all have one length, the mean of the two rows' (DESIGN.md "Net piece").
json lengthsBetweenRows(const Piece& p) {
    json lengths = json::array();
    if (p.bar.axis == BarAxis::Row)
        for (int r = 0; r + 1 < p.rows; ++r)
            lengths.push_back(p.barLength(r, 0, r + 1, 0));
    return lengths;
}

json pieceReport(const Sculpture& s, const CompiledSculpture& c, const Piece& p,
                 const std::vector<double>& tension) {
    const MassSpringSystem& sys = c.system;
    std::size_t bars = 0, ownedKnots = 0;
    double rope = 0, ropeMass = 0, maxTension = 0;
    std::optional<std::size_t> strongest; // the bar of the largest tension, if one is in tension
    for (std::size_t b = 0; b < sys.barCount(); ++b)
        if (sys.barPiece[b] == p.id) {
            ++bars;
            rope += sys.restLength[b];
            ropeMass += sys.linearDensity[b] * sys.restLength[b];
            if (tension[b] > maxTension) {
                maxTension = tension[b];
                strongest = b;
            }
        }
    for (std::size_t k = 0; k < sys.knotCount(); ++k)
        if (sys.refs[sys.refStart[k]].piece == p.id)
            ++ownedKnots;
    json lengths = json::array();
    const int count = p.bar.axis == BarAxis::Column ? p.columns : p.rows;
    for (int i = 0; i < count; ++i)
        lengths.push_back(p.bar.at(i));
    json seams = json::array();
    for (const Seam& seam : s.seams)
        if (seam.left == p.id || seam.right == p.id)
            seams.push_back(seamReport(s, sys, seam, p.id));
    const Material& m = p.material;
    const json strength = pieceStrength(m, maxTension);
    return {{"id", p.id.value},
            {"name", p.name},
            {"rows", p.rows},
            {"columns", p.columns},
            {"closed", p.closed},
            {"knots", std::size_t(p.rows) * std::size_t(p.columns)},
            {"knots_tied", ownedKnots},
            {"bars", bars},
            {"rope_length", rope},
            {"mass", ropeMass + m.knotMass * double(ownedKnots)},
            {"bar_axis", p.bar.axis == BarAxis::Column ? "column" : "row"},
            {"bar_lengths", lengths},
            {"bar_lengths_between_rows", lengthsBetweenRows(p)},
            {"max_tension", maxTension},
            {"max_tension_at", strongest ? barAt(sys, *strongest) : json(nullptr)},
            {"breaking_load", strength["breaking_load"]},
            {"utilisation", strength["utilisation"]},
            {"safety_factor", strength["safety_factor"]},
            {"material",
             {{"stiffness", m.stiffness},
              {"compression_ratio", m.compressionRatio},
              {"knot_mass", m.knotMass},
              {"linear_density", m.linearDensity},
              {"breaking_load", m.breakingLoad ? json(*m.breakingLoad) : json(nullptr)}}},
            {"colour", {p.colour.r, p.colour.g, p.colour.b}},
            {"top", pieceTop(s, p)},
            {"bottom", p.bottom ? railEdge(s, *p.bottom) : json(nullptr)},
            {"seams", seams}};
}

/// The load on a rail at one point: knots of pieces tied at the same place (two pieces on one
/// ring at the same columns) load it with the sum of their reactions.
struct PointLoad {
    double magnitude = 0;         ///< the largest summed reaction at one point, N
    std::size_t knots = 0;        ///< how many knots are tied at that point
    std::size_t sharedPoints = 0; ///< points where more than one knot is tied
};

/// Knots closer than this are tied at one point of the rail.
constexpr double kSamePoint = 1e-6; // m

/// `held` in the order of t; on a closed rail the last points may be the first ones again.
PointLoad largestPointLoad(const MassSpringSystem& sys, const std::vector<std::uint32_t>& held,
                           const std::vector<Vec3>& reaction) {
    std::vector<std::vector<std::uint32_t>> points;
    for (std::uint32_t k : held) {
        const bool same =
            !points.empty() &&
            (sys.position[points.back().front()] - sys.position[k]).norm() < kSamePoint;
        if (same)
            points.back().push_back(k);
        else
            points.push_back({k});
    }
    if (points.size() >= 2 &&
        (sys.position[points.back().front()] - sys.position[points.front().front()]).norm() <
            kSamePoint) {
        points.front().insert(points.front().end(), points.back().begin(), points.back().end());
        points.pop_back();
    }
    PointLoad out;
    for (const auto& point : points) {
        Vec3 sum;
        for (std::uint32_t k : point)
            sum += reaction[k];
        if (point.size() > 1)
            ++out.sharedPoints;
        if (sum.norm() > out.magnitude) {
            out.magnitude = sum.norm();
            out.knots = point.size();
        }
    }
    return out;
}

} // namespace

std::size_t countOverstretchedBars(const MassSpringSystem& sys) {
    std::size_t count = 0;
    for (std::size_t b = 0; b < sys.barCount(); ++b)
        count += barStrain(sys, b) > kOverstretchStrain ? 1 : 0;
    return count;
}

std::string overstretchWarning(std::size_t count) {
    return std::to_string(count) + " bars are stretched by more than " +
           std::to_string(int(kOverstretchStrain * 100)) +
           " % of their length, which rope cannot do: the net is tied between rails farther "
           "apart than it reaches (netsculpt report)";
}

nlohmann::json buildReport(const Sculpture& s, const CompiledSculpture& c,
                           const RelaxStatus& status) {
    const MassSpringSystem& sys = c.system;
    const bool physical = sys.knotCount() > 0;
    const std::vector<double> tension = sys.barCount() ? barTensions(sys) : std::vector<double>{};
    const std::vector<Vec3> reaction = physical ? reactions(sys, status.wind) : std::vector<Vec3>{};
    const double weight = physical ? totalWeight(sys) : 0.0;
    json report;
    report["units"] = {{"length", "m"},
                       {"mass", "kg"},
                       {"force", "N"},
                       {"strain", "fraction of the rest length (0.01 = 1 %)"},
                       {"utilisation", "fraction of the breaking load (0.25 = 25 %)"},
                       {"axes", "the sculpture's, z up"},
                       {"reaction",
                        "the force a rail exerts on the net; its load is the opposite"}};
    report["relaxed"] = status.relaxed;
    report["residual"] = physical ? residual(sys, status.wind) : 0.0;
    const Vec3 windForce = physical && status.wind ? totalWindForce(sys, *status.wind) : Vec3{};
    report["wind"] = status.wind ? json{{"direction", vec(status.wind->direction)},
                                        {"pressure", status.wind->pressure},
                                        {"force", vec(windForce)}}
                                 : json(nullptr);
    const RelaxResult& r = status.last;
    // Every run has a stop reason; a document that ran none (a snapshot opened) has no last run.
    report["relax"] = r.stopReason.empty()
                          ? json(nullptr)
                          : json{{"converged", r.converged}, {"residual", r.residual},
                                 {"steps", r.steps},         {"seconds", r.seconds},
                                 {"backend", r.backend},     {"stop_reason", r.stopReason}};
    report["knots"] = sys.knotCount();
    report["bars"] = sys.barCount();

    double mass = 0, rope = 0;
    for (double m : sys.mass)
        mass += m;
    for (double l : sys.restLength)
        rope += l;
    report["total_mass"] = mass;
    report["total_weight"] = weight;
    report["rope_length"] = rope;

    std::size_t slack = 0, strongest = 0, mostStretched = 0, overstretched = 0;
    double maxStrain = 0;
    for (std::size_t b = 0; b < sys.barCount(); ++b) {
        const double length = distance(sys.position[sys.barA[b]], sys.position[sys.barB[b]]);
        if (io::isSlack(length, sys.restLength[b]))
            ++slack;
        if (tension[b] > tension[strongest])
            strongest = b;
        const double strain = barStrain(sys, b);
        overstretched += strain > kOverstretchStrain ? 1 : 0;
        if (strain > maxStrain) {
            maxStrain = strain;
            mostStretched = b;
        }
    }
    report["slack_bars"] = slack;
    report["max_tension"] = sys.barCount() ? std::max(0.0, tension[strongest]) : 0.0;
    report["max_tension_at"] = sys.barCount() ? barAt(sys, strongest) : json(nullptr);
    report["max_strain"] = maxStrain;
    report["max_strain_at"] = maxStrain > 0 ? barAt(sys, mostStretched) : json(nullptr);
    report["overstretched_bars"] = overstretched;
    report["overstretch_limit"] = kOverstretchStrain;

    // At equilibrium the rails carry the whole weight: sum of reactions = -(total mass) g.
    Vec3 reactionSum;
    json rails = json::array();
    for (const auto& [id, rail] : s.rails) {
        std::vector<std::uint32_t> held;
        for (std::uint32_t k = 0; k < sys.knotCount(); ++k)
            if (sys.fixed[k] && sys.hold[k].rail == id)
                held.push_back(k);
        std::stable_sort(held.begin(), held.end(),
                         [&](auto a, auto b) { return sys.hold[a].t < sys.hold[b].t; });
        const auto onRail = s.piecesOnRail(id);
        Vec3 sum;
        double largest = 0;
        json points = json::array();
        for (std::uint32_t k : held) {
            KnotRef ref = sys.refs[sys.refStart[k]];
            for (PieceId p : onRail)
                if (refOf(sys, k, p).piece == p) {
                    ref = refOf(sys, k, p);
                    break;
                }
            sum += reaction[k];
            largest = std::max(largest, reaction[k].norm());
            points.push_back({{"piece", ref.piece.value},
                              {"row", ref.row},
                              {"column", ref.column},
                              {"t", sys.hold[k].t},
                              {"along", rail.curve().distanceAlong(sys.hold[k].t)},
                              {"position", vec(sys.worldPosition(k))},
                              {"reaction", vec(reaction[k])},
                              {"magnitude", reaction[k].norm()}});
        }
        reactionSum += sum;
        const PointLoad point = largestPointLoad(sys, held, reaction);
        rails.push_back(
            {{"id", id.value},
             {"name", rail.name},
             {"closed", rail.curve().closed()},
             {"length", rail.curve().length()},
             {"sampling",
              rail.curve().spec().sampling == Sampling::ArcLength ? "arc length" : "parameter"},
             {"start", vec(rail.curve().pointAt(0))},
             {"direction", vec(rail.curve().tangentAt(0))},
             {"attachments", held.size()},
             {"reaction", vec(sum)},
             {"max_reaction", largest},
             {"max_point_load", point.magnitude},
             {"max_point_load_knots", point.knots},
             {"shared_points", point.sharedPoints},
             {"points", std::move(points)}});
    }
    // The rails carry the weight and the wind: 0 - 0 is +0, so no "-0" is printed.
    const Vec3 expected = Vec3{} - s.gravity * mass - windForce;
    const Vec3 difference = reactionSum - expected;
    const double relative = weight > 0 ? difference.norm() / weight : 0.0;
    report["force_balance"] = {
        {"reaction_sum", vec(reactionSum)},
        {"expected", vec(expected)},
        {"difference", vec(difference)},
        {"relative_difference", relative},
        {"tolerance", status.tolerance},
        {"within_tolerance", relative <= status.tolerance},
        {"relaxed", status.relaxed},
        {"note",
         std::string(status.relaxed ? "relaxed: the rails' reactions should carry the "
                                      "total weight"
                                    : "not relaxed: the reactions balance the weight") +
             (windForce != Vec3{} ? " and the wind" : "") +
             (status.relaxed ? " to the tolerance" : " only after a converged relaxation")}};

    json pieces = json::array();
    for (const auto& [id, piece] : s.pieces)
        pieces.push_back(pieceReport(s, c, piece, tension));
    report.update(strengthSummary(pieces));
    report["pieces"] = std::move(pieces);
    report["rails"] = std::move(rails);
    return report;
}

} // namespace netsculpt
