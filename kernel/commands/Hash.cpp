// hashSculpture: FNV-1a (64-bit) over the model in a fixed order. Integers are hashed as 8
// little-endian bytes, doubles by their bits (so 0.0 and -0.0 differ, as they would on replay),
// strings and lists with their length first, so that no two different models share a byte stream.

#include "commands/Document.h"

#include <bit>
#include <cstring>

namespace netsculpt {

namespace {

class Fnv1a {
  public:
    void u64(std::uint64_t v) {
        for (int i = 0; i < 8; ++i) byte(std::uint8_t(v >> (8 * i)));
    }
    void i64(std::int64_t v) { u64(std::uint64_t(v)); }
    void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
    void flag(bool v) { byte(v ? 1 : 0); }
    void text(const std::string& s) {
        u64(s.size());
        for (char c : s) byte(std::uint8_t(c));
    }
    void vec3(const Vec3& v) {
        f64(v.x);
        f64(v.y);
        f64(v.z);
    }
    void list(const std::vector<double>& values) {
        u64(values.size());
        for (double v : values) f64(v);
    }
    std::uint64_t value() const { return h_; }

  private:
    std::uint64_t h_ = 0xcbf29ce484222325ull; // FNV offset basis
    void byte(std::uint8_t b) {
        h_ ^= b;
        h_ *= 0x100000001b3ull; // FNV prime
    }
};

void hashRailEdge(Fnv1a& h, const RailEdge& e) {
    h.u64(e.rail.value);
    h.f64(e.at);
    h.f64(e.step);
    h.i64(e.offset);
    h.flag(e.reverse);
}

void hashCurve(Fnv1a& h, const CurveSpec& spec) {
    h.flag(spec.spline);
    h.flag(spec.closed);
    h.i64(spec.sampling == Sampling::ArcLength ? 0 : 1);
    h.i64(spec.degree);
    h.u64(spec.points.size());
    for (const Vec3& p : spec.points) h.vec3(p);
    h.list(spec.knots);
    h.list(spec.weights);
}

void hashPiece(Fnv1a& h, const Piece& p) {
    h.u64(p.id.value);
    h.text(p.name);
    h.i64(p.rows);
    h.i64(p.columns);
    h.flag(p.closed);
    h.i64(p.bar.axis == BarAxis::Column ? 0 : 1);
    h.f64(p.bar.first);
    h.f64(p.bar.last);
    h.i64(p.bar.from);
    h.i64(p.bar.to);
    h.f64(p.material.stiffness);
    h.f64(p.material.compressionRatio);
    h.f64(p.material.knotMass);
    h.f64(p.material.linearDensity);
    // Hashed only when given, so that a model without one keeps the hash it had before the
    // field existed (a snapshot's stored hash is checked when it opens).
    if (p.material.breakingLoad) {
        h.flag(true);
        h.f64(*p.material.breakingLoad);
    }
    h.f64(p.colour.r);
    h.f64(p.colour.g);
    h.f64(p.colour.b);
    h.u64(p.top.index());
    if (p.onRail()) {
        hashRailEdge(h, p.railTop());
    } else {
        const ParentEdge& e = p.parentTop();
        h.u64(e.parents.size());
        for (PieceId parent : e.parents) h.u64(parent.value);
        h.i64(e.gear.num);
        h.i64(e.gear.den);
        h.flag(e.ringClosed);
        h.i64(e.offset);
        h.flag(e.whole);
    }
    h.flag(p.bottom.has_value());
    if (p.bottom) hashRailEdge(h, *p.bottom);
}

} // namespace

std::uint64_t hashSculpture(const Sculpture& s) {
    Fnv1a h;
    h.u64(s.rails.size());
    for (const auto& [id, rail] : s.rails) {
        h.u64(id.value);
        h.text(rail.name);
        hashCurve(h, rail.curve().spec());
    }
    h.u64(s.pieces.size());
    for (const auto& [id, piece] : s.pieces) hashPiece(h, piece);
    h.u64(s.seams.size());
    for (const Seam& seam : s.seams) {
        h.u64(seam.left.value);
        h.u64(seam.right.value);
    }
    h.u64(s.nextRailId);
    h.u64(s.nextPieceId);
    h.vec3(s.gravity);
    return h.value();
}

} // namespace netsculpt
