// DXF rails through dxflib (Import.h): a DL_CreationAdapter collects SPLINE, LWPOLYLINE,
// POLYLINE, LINE, ARC and CIRCLE entities of model space; DxfScan has checked the syntax first.

#include "geometry/Curve.h"
#include "io/DxfGeometry.h"
#include "io/DxfScan.h"
#include "io/ImportDetail.h"
#include "io/IoText.h"
#include "model/Error.h"

#include <dxflib/dl_creationadapter.h>
#include <dxflib/dl_dxf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <new>
#include <optional>

namespace netsculpt::io {

namespace {

/// $INSUNITS codes of the DXF reference, in metres (0 = unitless is not here).
struct DxfUnit {
    int code;
    const char* name;
    double metres;
};
constexpr std::array<DxfUnit, 24> kDxfUnits{{
    {1, "inches", 0.0254},
    {2, "feet", 0.3048},
    {3, "miles", 1609.344},
    {4, "millimetres", 1e-3},
    {5, "centimetres", 1e-2},
    {6, "metres", 1.0},
    {7, "kilometres", 1e3},
    {8, "microinches", 2.54e-8},
    {9, "mils", 2.54e-5},
    {10, "yards", 0.9144},
    {11, "angstroms", 1e-10},
    {12, "nanometres", 1e-9},
    {13, "microns", 1e-6},
    {14, "decimetres", 0.1},
    {15, "decametres", 10.0},
    {16, "hectometres", 100.0},
    {17, "gigametres", 1e9},
    {18, "astronomical units", 1.495978707e11},
    {19, "light years", 9.4607304725808e15},
    {20, "parsecs", 3.0856775814913673e16},
    {21, "US survey feet", 1200.0 / 3937.0},
    {22, "US survey inches", 100.0 / 3937.0},
    {23, "US survey yards", 3600.0 / 3937.0},
    {24, "US survey miles", 6336000.0 / 3937.0},
}};

struct Polyline {
    const DxfEntity* entity = nullptr;
    int flags = 0;
    bool light = false; ///< LWPOLYLINE (OCS, elevation) rather than POLYLINE
    Ocs ocs;
    double elevation = 0;
    std::vector<Vec3> vertices; ///< x, y, z as read; bulge in `bulges`
    std::vector<double> bulges;
};

class Collector final : public DL_CreationAdapter {
  public:
    Collector(const std::string& file, const DxfScan& scan) : file_(file), scan_(scan) {}

    std::optional<int> insunits;
    std::vector<std::pair<std::size_t, SourcedCurve>> curves; // (entity line, curve)
    std::map<std::string, std::vector<ChainPart>> chains;     // by layer
    std::vector<DxfSpline> splines;

    void processCodeValuePair(unsigned int code, const std::string&) override {
        const std::size_t line = 2 * groups_ + 1;
        ++groups_;
        if (code == 0) {
            finished_ = current_;
            current_ = line;
        }
    }
    void setVariableInt(const std::string& key, int value, int) override {
        if (key == "$INSUNITS")
            insunits = value;
    }

    void addLine(const DL_LineData& d) override {
        if (const DxfEntity* e = entity())
            chains[e->layer].push_back({{{d.x1, d.y1, d.z1}, {d.x2, d.y2, d.z2}}, e});
    }
    void addArc(const DL_ArcData& d) override {
        const DxfEntity* e = entity();
        if (!e)
            return;
        checkRadius(*e, d.radius);
        // Each angle is reduced on its own: the difference of two finite angles overflows
        // (1.7e308 and -1.7e308 degrees), and an infinite one left the sweep NaN.
        const double start = std::fmod(d.angle1, 360.0);
        double sweep = std::fmod(std::fmod(d.angle2, 360.0) - start, 360.0);
        if (sweep <= 0)
            sweep += 360.0;
        const double a0 = start * kRadiansPerDegree;
        const Vec3 centre{d.cx, d.cy, d.cz};
        std::vector<Vec3> pts{
            {d.cx + d.radius * std::cos(a0), d.cy + d.radius * std::sin(a0), d.cz}};
        appendArc(pts, centre, d.radius, a0, sweep * kRadiansPerDegree);
        const Ocs ocs = extrusion(*e);
        for (Vec3& p : pts)
            p = ocs.toWorld(p);
        chains[e->layer].push_back({std::move(pts), e});
    }
    void addCircle(const DL_CircleData& d) override {
        const DxfEntity* e = entity();
        if (!e)
            return;
        checkRadius(*e, d.radius);
        std::vector<Vec3> pts{{d.cx + d.radius, d.cy, d.cz}};
        appendArc(pts, {d.cx, d.cy, d.cz}, d.radius, 0, 2 * kPi);
        pts.pop_back(); // the closing point repeats the first
        const Ocs ocs = extrusion(*e);
        for (Vec3& p : pts)
            p = ocs.toWorld(p);
        CurveSpec spec;
        spec.points = std::move(pts);
        spec.closed = true;
        curves.push_back({e->line, {{e->railName(), std::move(spec)}, e->describe()}});
    }
    void addEllipse(const DL_EllipseData&) override {
        if (const DxfEntity* e = entity())
            fail(*e, "ELLIPSE is not read as a rail; convert it to a SPLINE or a POLYLINE in the "
                     "CAD program");
    }

    void addPolyline(const DL_PolylineData& d) override {
        const DxfEntity* e = entity();
        if (!e)
            return;
        polyline_ = Polyline{
            e,  d.flags, e->type == "LWPOLYLINE", extrusion(*e), getExtrusion()->getElevation(),
            {}, {}};
        if (!polyline_->light && (d.flags & (16 | 64)))
            fail(*e, "is a polygon or polyface mesh, not a curve; rails are curves");
        if (!polyline_->light && (d.flags & (2 | 4)))
            fail(*e, "is a curve-fit or spline-fit POLYLINE; convert it to a SPLINE (or explode "
                     "it) in the CAD program");
    }
    void addVertex(const DL_VertexData& d) override {
        if (!polyline_)
            return;
        polyline_->vertices.push_back({d.x, d.y, d.z});
        polyline_->bulges.push_back(d.bulge);
    }
    void endSequence() override { finishPolyline(); }

    void addSpline(const DL_SplineData& d) override {
        const DxfEntity* e = entity();
        spline_.reset();
        if (!e)
            return;
        // dxflib keeps the counts of the previous SPLINE when one is missing: the scan's counts
        // say how many values this entity really holds.
        if (e->count[10] == 0 && e->count[11] > 0)
            fail(*e,
                 "is defined by fit points only; rails need control points (in the CAD program, "
                 "convert the spline's fit points to control points)");
        if (e->count[10] == 0)
            fail(*e, "has no control points");
        spline_ = DxfSpline{e, int(d.degree), d.flags, {}, {}, {}};
    }
    void addControlPoint(const DL_ControlPointData& d) override {
        if (!spline_ || int(spline_->control.size()) == spline_->entity->count[10])
            return;
        spline_->control.push_back({d.x, d.y, d.z});
        spline_->weights.push_back(d.w);
    }
    void addKnot(const DL_KnotData& d) override {
        if (spline_ && int(spline_->knots.size()) < spline_->entity->count[40])
            spline_->knots.push_back(d.k);
    }
    void endEntity() override {
        if (polyline_ && polyline_->light)
            finishPolyline();
        if (spline_) {
            splines.push_back(std::move(*spline_));
            spline_.reset();
        }
    }

  private:
    static constexpr double kPi = 3.14159265358979323846;
    static constexpr double kRadiansPerDegree = kPi / 180.0;
    const std::string& file_;
    const DxfScan& scan_;
    std::size_t groups_ = 0, current_ = 0, finished_ = 0;
    std::optional<Polyline> polyline_;
    std::optional<DxfSpline> spline_;

    [[noreturn]] void fail(const DxfEntity& e, const std::string& what) const {
        throw UserError(file_ + ": " + e.describe() + ": " + what);
    }
    /// The entity dxflib is handing over, or null when it is not a model-space entity of the
    /// ENTITIES section (block definitions, paper space).
    const DxfEntity* entity() const {
        const DxfEntity* e = scan_.at(finished_);
        return e && !e->paperSpace ? e : nullptr;
    }
    void checkRadius(const DxfEntity& e, double r) const {
        if (!(r > 0))
            fail(e, "radius " + numberText(r) + " must be > 0");
    }
    Ocs extrusion(const DxfEntity& e) {
        const DL_Extrusion* x = getExtrusion();
        const Vec3 n{x->getDirection()[0], x->getDirection()[1], x->getDirection()[2]};
        if (!n.isFinite() || n == Vec3{0, 0, 0})
            fail(e, "has a zero extrusion direction (group codes 210/220/230)");
        return ocsOf(n);
    }
    void finishPolyline() {
        if (!polyline_)
            return;
        Polyline p = std::move(*polyline_);
        polyline_.reset();
        const bool closed = p.flags & 1;
        const bool world = !p.light && (p.flags & 8); // a 3D POLYLINE: WCS vertices, no bulges
        if (p.vertices.empty())
            fail(*p.entity, "has no vertices");
        std::vector<Vec3> pts;
        const std::size_t n = p.vertices.size();
        for (std::size_t i = 0; i < n; ++i) {
            Vec3 v = p.vertices[i];
            if (!world)
                v.z = p.elevation;
            if (i == 0)
                pts.push_back(v);
            if (i + 1 == n && !closed)
                break;
            Vec3 next = p.vertices[(i + 1) % n];
            if (!world)
                next.z = p.elevation;
            if (world)
                pts.push_back(next);
            else
                appendBulge(pts, v, next, p.bulges[i]);
        }
        if (closed)
            pts.pop_back(); // the closing segment's end is the first vertex
        if (!world)
            for (Vec3& v : pts)
                v = p.ocs.toWorld(v);
        CurveSpec spec;
        spec.points = std::move(pts);
        spec.closed = closed;
        curves.push_back(
            {p.entity->line, {{p.entity->railName(), std::move(spec)}, p.entity->describe()}});
    }
};

double fileUnits(const std::string& file, const std::optional<int>& insunits,
                 const ImportOptions& options) {
    const int code = insunits.value_or(0);
    std::string names;
    for (const auto& u : unitNames())
        names += (names.empty() ? "" : ", ") + u;
    if (code == 0) {
        if (!options.units.empty())
            return metresPerUnit(options.units);
        throw UserError(
            file + ": the drawing has no units ($INSUNITS is " +
            (insunits ? std::string("0, unitless") : std::string("not set")) +
            "); set the drawing units in the CAD program, or say which unit its numbers are "
            "in when importing (units = one of " +
            names + ")");
    }
    const auto it = std::find_if(kDxfUnits.begin(), kDxfUnits.end(),
                                 [&](const DxfUnit& u) { return u.code == code; });
    if (it == kDxfUnits.end())
        throw UserError(
            file + ": $INSUNITS is " + std::to_string(code) +
            ", which is not a DXF unit code (1 to 24, or 0 for unitless); fix the drawing's units "
            "in the CAD program");
    if (!options.units.empty()) {
        const double asked = metresPerUnit(options.units);
        if (std::abs(asked - it->metres) > 1e-12 * it->metres)
            throw UserError(file + ": the drawing is in " + it->name + " ($INSUNITS " +
                            std::to_string(code) + ") but units = \"" + options.units +
                            "\" was given; leave units out or fix the drawing");
    }
    return it->metres;
}

} // namespace

std::vector<NamedCurve> importDxf(const std::filesystem::path& path, const ImportOptions& options) {
    const std::string file = displayName(path);
    const DxfScan scan = scanDxf(file, readWholeFile(path));
    Collector collector(file, scan);
    DL_Dxf dxf;
    try {
        if (!dxf.in(path.string(), &collector))
            throw UserError(file + ": cannot open the file");
    } catch (const std::bad_alloc&) {
        throw UserError(file + ": the drawing declares more data than can be held in memory");
    }
    const double metres = fileUnits(file, collector.insunits, options);

    std::vector<std::pair<std::size_t, SourcedCurve>> all = std::move(collector.curves);
    for (const DxfSpline& s : collector.splines)
        all.push_back({s.entity->line, splineCurve(file, s)});
    for (const auto& [layer, parts] : collector.chains) {
        for (auto& chain : joinChains(file, parts))
            all.push_back({chain.order, std::move(chain)});
    }
    if (all.empty()) {
        std::map<std::string, int> types;
        for (const auto& e : scan.entities)
            ++types[e.type];
        std::string seen;
        for (const auto& [type, count] : types)
            seen += (seen.empty() ? "" : ", ") + std::to_string(count) + " " + type;
        throw UserError(
            file +
            ": holds no rails (SPLINE, LWPOLYLINE, POLYLINE, LINE, ARC or CIRCLE in model space)" +
            (seen.empty() ? std::string("; it has no entities") : "; it has " + seen));
    }
    std::stable_sort(all.begin(), all.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<SourcedCurve> curves;
    for (auto& [line, curve] : all)
        curves.push_back(std::move(curve));
    return finishRails(file, std::move(curves), metres);
}

} // namespace netsculpt::io
