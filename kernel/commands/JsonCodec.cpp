#include "commands/JsonCodec.h"

#include "model/Error.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <type_traits>

namespace netsculpt::codec {

namespace {

std::string typeName(const Json& j) { return j.type_name(); }

Json numberList(const std::vector<double>& values, const char* what) {
    Json out = Json::array();
    for (double v : values) out.push_back(number(v, what));
    return out;
}

Json railEdgeJson(const RailEdge& e) {
    Json j = Json::object();
    j["rail"] = e.rail.value;
    j["at"] = number(e.at, "rail position");
    j["step"] = number(e.step, "rail step");
    j["offset"] = e.offset;
    j["reverse"] = e.reverse;
    return j;
}

RailEdge readRailEdge(const Json& j, const std::string& what) {
    ObjectReader r(j, what);
    RailEdge e;
    e.rail = RailId(r.id("rail"));
    e.at = r.real("at");
    e.step = r.real("step");
    e.offset = r.integer("offset");
    e.reverse = r.boolean("reverse");
    r.finish();
    return e;
}

/// Refuses arrays and objects nested deeper than kMaxJsonNesting. Our files nest 8 levels at
/// most (a snapshot's history entry holding an import's rail points), and nlohmann's copy and
/// dump recurse once per level: 100,000 nested brackets in a damaged file overflowed the stack.
void checkNesting(std::string_view text) {
    int depth = 0;
    bool inString = false, escaped = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonNesting)
                throw UserError("bad JSON: arrays and objects nested more than " +
                                std::to_string(kMaxJsonNesting) + " levels deep (at character " +
                                std::to_string(i + 1) + ")");
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

} // namespace

std::string gearText(Gear g) { return toString(g); }

Gear gearFromText(const std::string& text, const std::string& what) {
    // "n" or "n/d" with small positive integers; whether the gear is allowed is the edit's check.
    Gear g{0, 1};
    const char* p = text.data();
    const char* end = p + text.size();
    auto r = std::from_chars(p, end, g.num);
    if (r.ec != std::errc() || g.num <= 0) throw UserError(what + ": gear must look like \"2\" or \"1/2\", got \"" + text + "\"");
    if (r.ptr != end) {
        if (*r.ptr != '/') throw UserError(what + ": gear must look like \"2\" or \"1/2\", got \"" + text + "\"");
        auto r2 = std::from_chars(r.ptr + 1, end, g.den);
        if (r2.ec != std::errc() || r2.ptr != end || g.den <= 0)
            throw UserError(what + ": gear must look like \"2\" or \"1/2\", got \"" + text + "\"");
    }
    return g;
}

Json materialJson(const Material& m, Json j) {
    j["stiffness"] = number(m.stiffness, "stiffness");
    j["compression_ratio"] = number(m.compressionRatio, "compression_ratio");
    j["knot_mass"] = number(m.knotMass, "knot_mass");
    j["linear_density"] = number(m.linearDensity, "linear_density");
    // Written only when given: journals and snapshots without one read as they always did.
    if (m.breakingLoad)
        j["breaking_load"] = number(*m.breakingLoad, "breaking_load");
    return j;
}

Material readMaterial(ObjectReader& r) {
    Material m;
    m.stiffness = r.real("stiffness");
    m.compressionRatio = r.real("compression_ratio");
    m.knotMass = r.real("knot_mass");
    m.linearDensity = r.real("linear_density");
    if (r.has("breaking_load"))
        m.breakingLoad = r.real("breaking_load");
    return m;
}

Json colourJson(const Colour& c) {
    return Json::array({number(c.r, "colour"), number(c.g, "colour"), number(c.b, "colour")});
}

Colour readColour(ObjectReader& r, const char* key) {
    const Vec3 v = r.vec3(key);
    return Colour{v.x, v.y, v.z};
}

Json parseJson(std::string_view text) {
    checkNesting(text);
    try {
        return Json::parse(text.begin(), text.end());
    } catch (const Json::parse_error& e) {
        throw UserError(std::string("bad JSON: ") + e.what());
    } catch (const Json::out_of_range& e) {
        // nlohmann's "[json.exception.out_of_range.406] number overflow parsing '1e400'"
        const std::string what = e.what();
        const std::size_t detail = what.find("] ");
        throw UserError("bad JSON: " +
                        (detail == std::string::npos ? what : what.substr(detail + 2)) +
                        " (numbers must lie within +-1.8e308)");
    }
}

Json number(double value, const char* what) {
    if (!std::isfinite(value))
        throw UserError(std::string(what) + " must be a finite number to be journaled, got " + formatNumber(value));
    return Json(value);
}

// ---- ObjectReader ----

ObjectReader::ObjectReader(const Json& object, std::string what) : object_(object), what_(std::move(what)) {
    if (!object_.is_object()) throw UserError(what_ + " must be a JSON object, got " + typeName(object_));
}

bool ObjectReader::has(const char* key) const { return object_.contains(key); }

void ObjectReader::fail(const char* key, const std::string& expected) const {
    throw UserError(what_ + ": \"" + key + "\" must be " + expected);
}

const Json& ObjectReader::raw(const char* key) {
    auto it = object_.find(key);
    if (it == object_.end()) throw UserError(what_ + ": \"" + key + "\" is missing");
    read_.insert(key);
    return *it;
}

int ObjectReader::integer(const char* key) {
    const Json& v = raw(key);
    if (v.is_number_unsigned()) {
        if (v.get<std::uint64_t>() <= std::uint64_t(std::numeric_limits<int>::max())) return int(v.get<std::uint64_t>());
    } else if (v.is_number_integer()) {
        const std::int64_t i = v.get<std::int64_t>();
        if (i >= std::numeric_limits<int>::min() && i <= std::numeric_limits<int>::max()) return int(i);
    }
    fail(key, "a whole number (32-bit), got " + v.dump());
}

std::uint32_t ObjectReader::id(const char* key) {
    const Json& v = raw(key);
    if (v.is_number_unsigned() && v.get<std::uint64_t>() <= 0xffffffffu) return std::uint32_t(v.get<std::uint64_t>());
    fail(key, "an id (a whole number >= 0), got " + v.dump());
}

std::uint64_t ObjectReader::unsignedInteger(const char* key) {
    const Json& v = raw(key);
    if (v.is_number_unsigned()) return v.get<std::uint64_t>();
    fail(key, "a whole number >= 0, got " + v.dump());
}

double ObjectReader::real(const char* key) { return realValue(raw(key), what_ + ": \"" + key + "\""); }

bool ObjectReader::boolean(const char* key) {
    const Json& v = raw(key);
    if (!v.is_boolean()) fail(key, "true or false, got " + v.dump());
    return v.get<bool>();
}

std::string ObjectReader::text(const char* key) {
    const Json& v = raw(key);
    if (!v.is_string()) fail(key, "a string, got " + v.dump());
    return v.get<std::string>();
}

Vec3 ObjectReader::vec3(const char* key) { return vec3Value(raw(key), what_ + ": \"" + key + "\""); }

void ObjectReader::finish() const {
    for (auto it = object_.begin(); it != object_.end(); ++it)
        if (!read_.count(it.key())) throw UserError(what_ + ": unknown key \"" + it.key() + "\"");
}

double realValue(const Json& value, const std::string& what) {
    if (!value.is_number()) throw UserError(what + " must be a number, got " + value.dump());
    return value.get<double>();
}

Vec3 vec3Value(const Json& value, const std::string& what) {
    if (!value.is_array() || value.size() != 3) throw UserError(what + " must be [x, y, z], got " + value.dump());
    return Vec3{realValue(value[0], what), realValue(value[1], what), realValue(value[2], what)};
}

Json vec3Json(const Vec3& v, const char* what) {
    return Json::array({number(v.x, what), number(v.y, what), number(v.z, what)});
}

// ---- curves ----

Json curveJson(const CurveSpec& spec) {
    Json j = Json::object();
    Json points = Json::array();
    for (const Vec3& p : spec.points) points.push_back(vec3Json(p, "rail point"));
    j[spec.spline ? "control" : "points"] = std::move(points);
    if (spec.spline || spec.degree != 1) j["degree"] = spec.degree;
    if (!spec.knots.empty()) j["knots"] = numberList(spec.knots, "rail knot");
    if (!spec.weights.empty()) j["weights"] = numberList(spec.weights, "rail weight");
    j["closed"] = spec.closed;
    if (spec.sampling != Sampling::ArcLength) j["sampling"] = "parameter";
    return j;
}

CurveSpec readCurve(ObjectReader& r) {
    CurveSpec spec;
    if (r.has("points") == r.has("control")) throw UserError("a rail needs \"points\" (a polyline) or \"control\" (a B-spline), not both");
    spec.spline = r.has("control");
    const Json& points = r.raw(spec.spline ? "control" : "points");
    if (!points.is_array()) throw UserError("rail points must be an array of [x, y, z]");
    for (const Json& p : points) spec.points.push_back(vec3Value(p, "rail point"));
    if (r.has("degree")) spec.degree = r.integer("degree");
    else if (spec.spline) spec.degree = 3;
    for (auto [key, out] : {std::pair{"knots", &spec.knots}, std::pair{"weights", &spec.weights}}) {
        if (!r.has(key)) continue;
        const Json& list = r.raw(key);
        if (!list.is_array()) throw UserError(std::string("rail ") + key + " must be an array of numbers");
        for (const Json& v : list) out->push_back(realValue(v, std::string("rail ") + key));
    }
    if (r.has("closed")) spec.closed = r.boolean("closed");
    if (r.has("sampling")) {
        const std::string sampling = r.text("sampling");
        if (sampling == "parameter") spec.sampling = Sampling::Parameter;
        else if (sampling != "arclength")
            throw UserError("rail sampling must be \"arclength\" or \"parameter\", got \"" + sampling + "\"");
    }
    return spec;
}

// ---- the model (snapshots) ----

Json sculptureJson(const Sculpture& s) {
    Json j = Json::object();
    Json rails = Json::array();
    for (const auto& [id, rail] : s.rails) {
        Json one = Json::object();
        one["id"] = id.value;
        one["name"] = rail.name;
        one.update(curveJson(rail.curve().spec()));
        rails.push_back(std::move(one));
    }
    j["rails"] = std::move(rails);
    Json pieces = Json::array();
    for (const auto& [id, p] : s.pieces) {
        Json one = Json::object();
        one["id"] = id.value;
        one["name"] = p.name;
        one["rows"] = p.rows;
        one["columns"] = p.columns;
        one["closed"] = p.closed;
        one["bar"] = Json{{"axis", p.bar.axis == BarAxis::Column ? "column" : "row"},
                          {"first", number(p.bar.first, "bar")},
                          {"last", number(p.bar.last, "bar")},
                          {"from", p.bar.from},
                          {"to", p.bar.to}};
        one["material"] = materialJson(p.material, Json::object());
        one["colour"] = colourJson(p.colour);
        if (p.onRail()) {
            one["top"] = railEdgeJson(p.railTop());
        } else {
            const ParentEdge& e = p.parentTop();
            Json parents = Json::array();
            for (PieceId parent : e.parents) parents.push_back(parent.value);
            one["top"] = Json{{"parents", std::move(parents)}, {"gear", gearText(e.gear)},
                              {"ring_closed", e.ringClosed}, {"offset", e.offset}, {"whole", e.whole}};
        }
        if (p.bottom) one["bottom"] = railEdgeJson(*p.bottom);
        pieces.push_back(std::move(one));
    }
    j["pieces"] = std::move(pieces);
    Json seams = Json::array();
    for (const Seam& seam : s.seams) seams.push_back(Json::array({seam.left.value, seam.right.value}));
    j["seams"] = std::move(seams);
    j["next_rail_id"] = s.nextRailId;
    j["next_piece_id"] = s.nextPieceId;
    j["gravity"] = vec3Json(s.gravity, "gravity");
    return j;
}

Sculpture decodeSculpture(const Json& model) {
    ObjectReader r(model, "model");
    Sculpture s;
    const auto array = [&](const char* key) -> const Json& {
        const Json& a = r.raw(key);
        if (!a.is_array()) throw UserError(std::string("model: \"") + key + "\" must be an array");
        return a;
    };
    for (const Json& one : array("rails")) {
        ObjectReader rr(one, "model rail");
        Rail rail;
        rail.id = RailId(rr.id("id"));
        rail.name = rr.text("name");
        rail.shape = std::make_shared<const Curve>(Curve::build(readCurve(rr)));
        rr.finish();
        if (!s.rails.emplace(rail.id, rail).second) throw UserError("model: " + toString(rail.id) + " appears twice");
    }
    for (const Json& one : array("pieces")) {
        ObjectReader pr(one, "model piece");
        Piece p;
        p.id = PieceId(pr.id("id"));
        p.name = pr.text("name");
        p.rows = pr.integer("rows");
        p.columns = pr.integer("columns");
        p.closed = pr.boolean("closed");
        ObjectReader br(pr.raw("bar"), toString(p.id) + " bar");
        const std::string axis = br.text("axis");
        if (axis != "column" && axis != "row") throw UserError(toString(p.id) + ": bar axis must be \"column\" or \"row\"");
        p.bar = BarProfile{axis == "column" ? BarAxis::Column : BarAxis::Row, br.real("first"), br.real("last"),
                           br.integer("from"), br.integer("to")};
        br.finish();
        ObjectReader mr(pr.raw("material"), toString(p.id) + " material");
        p.material = readMaterial(mr);
        mr.finish();
        p.colour = readColour(pr, "colour");
        const Json& top = pr.raw("top");
        if (top.is_object() && top.contains("parents")) {
            ObjectReader tr(top, toString(p.id) + " top");
            ParentEdge e;
            const Json& parents = tr.raw("parents");
            if (!parents.is_array()) throw UserError(toString(p.id) + ": top parents must be an array");
            for (const Json& parent : parents) {
                if (!parent.is_number_unsigned()) throw UserError(toString(p.id) + ": a parent id must be a whole number");
                e.parents.push_back(PieceId(parent.get<std::uint32_t>()));
            }
            e.gear = gearFromText(tr.text("gear"), toString(p.id) + " top");
            e.ringClosed = tr.boolean("ring_closed");
            e.offset = tr.integer("offset");
            e.whole = tr.boolean("whole");
            tr.finish();
            p.top = e;
        } else {
            p.top = readRailEdge(top, toString(p.id) + " top");
        }
        if (pr.has("bottom")) p.bottom = readRailEdge(pr.raw("bottom"), toString(p.id) + " bottom");
        pr.finish();
        if (!s.pieces.emplace(p.id, p).second) throw UserError("model: " + toString(p.id) + " appears twice");
    }
    for (const Json& seam : array("seams")) {
        if (!seam.is_array() || seam.size() != 2 || !seam[0].is_number_unsigned() || !seam[1].is_number_unsigned())
            throw UserError("model: a seam must be [left piece, right piece], got " + seam.dump());
        s.seams.push_back({PieceId(seam[0].get<std::uint32_t>()), PieceId(seam[1].get<std::uint32_t>())});
    }
    s.nextRailId = r.id("next_rail_id");
    s.nextPieceId = r.id("next_piece_id");
    s.gravity = r.vec3("gravity");
    r.finish();
    return s;
}

} // namespace netsculpt::codec
