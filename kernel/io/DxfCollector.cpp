// A DL_CreationAdapter collecting SPLINE, LWPOLYLINE, POLYLINE, LINE, ARC, CIRCLE and INSERT
// entities of model space and of block definitions (DxfCollector.h); DxfScan has checked the
// syntax first.

#include "io/DxfCollector.h"

#include "io/IoText.h"
#include "model/Error.h"

#include <dxflib/dl_creationadapter.h>
#include <dxflib/dl_dxf.h>

#include <clocale>
#include <cmath>
#include <cstdio>
#include <locale>
#include <memory>
#include <mutex>
#include <new>

namespace netsculpt::io {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadiansPerDegree = kPi / 180.0;

struct Polyline {
    const DxfEntity* entity = nullptr;
    int flags = 0;
    bool light = false; ///< LWPOLYLINE (OCS, elevation) rather than POLYLINE
    Ocs ocs;
    double elevation = 0;
    std::vector<Vec3> vertices; ///< x, y, z as read; bulge in `bulges`
    std::vector<double> bulges;
};

/// The points of a polyline: bulges sampled, in world (or block) coordinates. A polyline whose
/// last vertex lies on its first (within 1e-6 of its extent) is closed, flagged or not, and the
/// repeated vertex is dropped: CAD programs snap an outline shut without setting the flag.
CurveSpec polylinePoints(const Polyline& p) {
    const bool world = !p.light && (p.flags & 8); // a 3D POLYLINE: WCS vertices, no bulges
    std::vector<Vec3> vertices = p.vertices;
    std::vector<double> bulges = p.bulges;
    if (!world)
        for (Vec3& v : vertices)
            v.z = p.elevation;
    const double tolerance = 1e-6 * extent(vertices);
    bool closed = p.flags & 1;
    while (vertices.size() > 2 && distance(vertices.back(), vertices.front()) <= tolerance) {
        vertices.pop_back(); // its bulge (to the first vertex) is that of a zero-length segment
        bulges.pop_back();
        closed = true;
    }
    std::vector<Vec3> pts{vertices[0]};
    const std::size_t n = vertices.size();
    for (std::size_t i = 0; i < n && (closed || i + 1 < n); ++i) {
        const Vec3& next = vertices[(i + 1) % n];
        if (world)
            pts.push_back(next);
        else
            appendBulge(pts, vertices[i], next, bulges[i]);
    }
    if (closed)
        pts.pop_back(); // the closing segment's end is the first vertex
    if (!world)
        for (Vec3& v : pts)
            v = p.ocs.toWorld(v);
    CurveSpec spec;
    spec.points = std::move(pts);
    spec.closed = closed;
    return spec;
}

class Collector final : public DL_CreationAdapter {
  public:
    explicit Collector(const DxfScan& scan) : scan_(scan) {}

    DxfDrawing drawing;

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
            drawing.insunits = value;
    }
    void addBlock(const DL_BlockData& d) override {
        DxfContent& block = drawing.blocks[d.name];
        block.base = {d.bpx, d.bpy, d.bpz};
        block.defined = true;
    }

    void addLine(const DL_LineData& d) override {
        if (const DxfEntity* e = entity())
            content(*e).parts.push_back({e, {{d.x1, d.y1, d.z1}, {d.x2, d.y2, d.z2}}});
    }
    void addArc(const DL_ArcData& d) override {
        guarded([&](const DxfEntity& e) {
            checkRadius(e, d.radius);
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
            const Ocs ocs = extrusion(e);
            for (Vec3& p : pts)
                p = ocs.toWorld(p);
            content(e).parts.push_back({&e, std::move(pts)});
        });
    }
    void addCircle(const DL_CircleData& d) override {
        guarded([&](const DxfEntity& e) {
            checkRadius(e, d.radius);
            std::vector<Vec3> pts{{d.cx + d.radius, d.cy, d.cz}};
            appendArc(pts, {d.cx, d.cy, d.cz}, d.radius, 0, 2 * kPi);
            pts.pop_back(); // the closing point repeats the first
            const Ocs ocs = extrusion(e);
            for (Vec3& p : pts)
                p = ocs.toWorld(p);
            CurveSpec spec;
            spec.points = std::move(pts);
            spec.closed = true;
            content(e).curves.push_back({&e, std::move(spec)});
        });
    }
    void addEllipse(const DL_EllipseData&) override {
        guarded([&](const DxfEntity& e) {
            fail(e, "ELLIPSE is not read as a rail; convert it to a SPLINE or a POLYLINE in the "
                    "CAD program");
        });
    }
    void addInsert(const DL_InsertData& d) override {
        guarded([&](const DxfEntity& e) {
            content(e).inserts.push_back(DxfInsert{&e, d.name, {d.ipx, d.ipy, d.ipz},
                                                   {d.sx, d.sy, d.sz}, d.angle, extrusion(e),
                                                   d.cols, d.rows});
        });
    }

    void addPolyline(const DL_PolylineData& d) override {
        polyline_.reset();
        guarded([&](const DxfEntity& e) {
            Polyline p{&e, d.flags, e.type == "LWPOLYLINE", extrusion(e),
                       getExtrusion()->getElevation(), {}, {}};
            if (!p.light && (d.flags & (16 | 64)))
                fail(e, "is a polygon or polyface mesh, not a curve; rails are curves");
            if (!p.light && (d.flags & (2 | 4)))
                fail(e, "is a curve-fit or spline-fit POLYLINE; convert it to a SPLINE (or "
                        "explode it) in the CAD program");
            polyline_ = std::move(p);
        });
    }
    void addVertex(const DL_VertexData& d) override {
        if (!polyline_)
            return;
        polyline_->vertices.push_back({d.x, d.y, d.z});
        polyline_->bulges.push_back(d.bulge);
    }
    void endSequence() override { finishPolyline(); }

    void addSpline(const DL_SplineData& d) override {
        spline_.reset();
        guarded([&](const DxfEntity& e) {
            // dxflib keeps the counts of the previous SPLINE when one is missing: the scan's
            // counts say how many values this entity really holds.
            if (e.count[10] == 0 && e.count[11] > 0)
                fail(e, "is defined by fit points only; rails need control points (in the CAD "
                        "program, convert the spline's fit points to control points)");
            if (e.count[10] == 0)
                fail(e, "has no control points");
            spline_ = DxfSpline{&e, int(d.degree), d.flags, {}, {}, {}};
        });
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
            content(*spline_->entity).splines.push_back(std::move(*spline_));
            spline_.reset();
        }
    }

  private:
    const DxfScan& scan_;
    std::size_t groups_ = 0, current_ = 0, finished_ = 0;
    std::optional<Polyline> polyline_;
    std::optional<DxfSpline> spline_;

    /// Why the current entity cannot be a rail; guarded() turns it into a UserError or keeps it.
    struct Refusal {
        std::string reason;
    };
    [[noreturn]] static void fail(const DxfEntity&, const std::string& reason) {
        throw Refusal{reason};
    }
    /// The entity dxflib is handing over, or null when it is neither in model space nor in a
    /// block definition (paper space, tables, objects).
    const DxfEntity* entity() const {
        const DxfEntity* e = scan_.at(finished_);
        return e && (!e->block.empty() || !e->paperSpace) ? e : nullptr;
    }
    DxfContent& content(const DxfEntity& e) {
        return e.block.empty() ? drawing.model : drawing.blocks[e.block];
    }
    /// Runs `read` on the current entity. A refusal is kept, not thrown: it counts only for an
    /// entity that is read (its layer chosen, its block inserted), which is known after placing.
    template <class Read> void guarded(Read&& read) {
        const DxfEntity* e = entity();
        if (!e)
            return;
        try {
            read(*e);
        } catch (const Refusal& refusal) {
            refuse(*e, refusal.reason);
        }
    }
    void refuse(const DxfEntity& e, const std::string& reason) {
        content(e).refusals.push_back({&e, reason});
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
        if (p.vertices.empty())
            return refuse(*p.entity, "has no vertices");
        content(*p.entity).curves.push_back({p.entity, polylinePoints(p)});
    }
};

/// dxflib reads numbers with a std::istringstream, which takes the global C++ locale: under
/// one whose decimal point is "," it misreads "1.5". While it exists, the global locale
/// is the classic one. When it already is (the usual case) nothing is switched; otherwise both
/// the C++ global locale and the C locale (which std::locale::global sets too) are put back
/// afterwards, under a mutex so that two imports do not interleave their switches. The switch
/// is process-wide: another thread parsing numbers by the global locale meanwhile would see it.
class ClassicLocale {
  public:
    ClassicLocale() : lock_(mutex()) {
        if (std::locale() == std::locale::classic())
            return;
        const char* c = std::setlocale(LC_ALL, nullptr);
        cLocale_ = c ? c : "C";
        previous_ = std::locale::global(std::locale::classic());
    }
    ~ClassicLocale() {
        if (!previous_)
            return;
        std::locale::global(*previous_);
        std::setlocale(LC_ALL, cLocale_.c_str());
    }
    ClassicLocale(const ClassicLocale&) = delete;
    ClassicLocale& operator=(const ClassicLocale&) = delete;

  private:
    static std::mutex& mutex() {
        static std::mutex m;
        return m;
    }
    std::lock_guard<std::mutex> lock_;
    std::optional<std::locale> previous_;
    std::string cLocale_;
};

} // namespace

DxfDrawing collectDxf(const std::string& file, const DxfScan& scan, const std::string& text) {
    Collector collector(scan);
    DL_Dxf dxf;
    // dxflib reads the decoded text, not the file. Its stream reader does not report the group
    // codes (processCodeValuePair), which tie each entity to the scan's: it reads a FILE over
    // the text, as DL_Dxf::in(path) does over the file, in the classic locale.
    const std::unique_ptr<FILE, int (*)(FILE*)> stream(
        fmemopen(const_cast<char*>(text.data()), text.size(), "r"), &std::fclose);
    if (!stream)
        throw UserError(file + ": cannot read the file");
    const ClassicLocale classic;
    try {
        while (dxf.readDxfGroups(stream.get(), &collector)) {
        }
    } catch (const std::bad_alloc&) {
        throw UserError(file + ": the drawing declares more data than can be held in memory");
    }
    return std::move(collector.drawing);
}

} // namespace netsculpt::io
