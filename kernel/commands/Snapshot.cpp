#include "commands/Snapshot.h"

#include "commands/Document.h"
#include "commands/JsonCodec.h"
#include "model/Error.h"

#include <cstdio>

namespace netsculpt {

namespace {

using codec::Json;

std::string hex16(std::uint64_t v) {
    char buffer[17];
    std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(v));
    return buffer;
}

} // namespace

std::string encodeSnapshot(const Sculpture& model, const std::vector<JournalEntry>& history,
                           const SnapshotShape& shape) {
    Json j = Json::object();
    j["hash"] = hex16(hashSculpture(model));
    j["model"] = codec::sculptureJson(model);
    Json entries = Json::array();
    for (const JournalEntry& e : history) entries.push_back(codec::entryObject(e));
    j["history"] = std::move(entries);
    Json flat = Json::array();
    for (const Vec3& p : shape.positions) {
        flat.push_back(codec::number(p.x, "knot position"));
        flat.push_back(codec::number(p.y, "knot position"));
        flat.push_back(codec::number(p.z, "knot position"));
    }
    j["shape"] = Json{{"warm", shape.warm},
                      {"relaxed", shape.relaxed},
                      {"origin", codec::vec3Json(shape.origin, "the shape's origin")},
                      {"positions", std::move(flat)}};
    if (shape.wind)
        j["shape"]["wind"] = Json{{"direction", codec::vec3Json(shape.wind->direction, "wind")},
                                  {"pressure", codec::number(shape.wind->pressure, "wind")}};
    if (shape.residual)
        j["shape"]["residual"] = codec::number(*shape.residual, "the shape's residual");
    if (shape.tolerance)
        j["shape"]["tolerance"] = codec::number(*shape.tolerance, "the shape's tolerance");
    std::string text = std::string(kSnapshotMagic) + " " + std::to_string(kSnapshotFormat) + "\n";
    try {
        text += j.dump(-1, ' ', true);
    } catch (const Json::type_error&) {
        throw UserError("snapshot: names and paths must be valid UTF-8 text");
    }
    return text + "\n";
}

SnapshotData decodeSnapshot(std::string_view text, const std::string& name) {
    const std::size_t headerEnd = text.find('\n');
    const std::string_view header = withoutCarriageReturn(text.substr(0, headerEnd));
    const std::string prefix = std::string(kSnapshotMagic) + " ";
    if (headerEnd == std::string_view::npos || header.substr(0, prefix.size()) != prefix)
        throw UserError(name + " is not a netsculpt snapshot (no \"" + prefix + "1\" line)");
    const std::string_view versionText = header.substr(prefix.size());
    if (versionText.empty() || versionText.size() > 8 ||
        versionText.find_first_not_of("0123456789") != std::string_view::npos)
        throw UserError(name + " line 1: bad snapshot format version \"" + std::string(versionText) + "\"");
    const int version = std::stoi(std::string(versionText));
    if (version > kSnapshotFormat)
        throw UserError(name + ": snapshot format " + std::to_string(version) + " is newer than this netsculpt (reads " +
                        std::to_string(kSnapshotFormat) + ")");
    Json j;
    try {
        j = codec::parseJson(text.substr(headerEnd + 1));
    } catch (const UserError& e) {
        throw UserError(name + ": the snapshot is damaged (" + e.what() + ")");
    }
    try {
        SnapshotData out;
        codec::ObjectReader r(j, "snapshot");
        const std::string hashText = r.text("hash");
        std::size_t used = 0;
        out.hash = std::stoull(hashText, &used, 16);
        if (used != hashText.size() || hashText.size() != 16) throw UserError("\"hash\" must be 16 hex digits");
        out.model = codec::decodeSculpture(r.raw("model"));
        const Json& history = r.raw("history");
        if (!history.is_array()) throw UserError("\"history\" must be an array of entries");
        for (const Json& e : history) out.history.push_back(codec::decodeEntryObject(e));
        codec::ObjectReader sr(r.raw("shape"), "snapshot shape");
        out.shape.warm = sr.boolean("warm");
        out.shape.relaxed = sr.boolean("relaxed");
        if (version >= 2) out.shape.origin = sr.vec3("origin");
        if (sr.has("wind")) {
            codec::ObjectReader wr(sr.raw("wind"), "snapshot shape wind");
            Wind wind{wr.vec3("direction"), wr.real("pressure")};
            wr.finish();
            validatedWindDirection(wind); // UserError for a zero, infinite or negative one
            out.shape.wind = wind;
        }
        if (sr.has("residual")) out.shape.residual = sr.real("residual");
        if (sr.has("tolerance")) {
            const double tolerance = sr.real("tolerance");
            if (!(tolerance > 0 && tolerance <= kMaxTolerance))
                throw UserError("the shape's tolerance must be > 0 and at most " +
                                formatNumber(kMaxTolerance) + ", got " + formatNumber(tolerance));
            out.shape.tolerance = tolerance;
        }
        const Json& flat = sr.raw("positions");
        if (!flat.is_array() || flat.size() % 3 != 0)
            throw UserError("\"positions\" must be a flat array of x, y, z numbers");
        out.shape.positions.reserve(flat.size() / 3);
        for (std::size_t i = 0; i < flat.size(); i += 3)
            out.shape.positions.push_back({codec::realValue(flat[i], "a position"),
                                           codec::realValue(flat[i + 1], "a position"),
                                           codec::realValue(flat[i + 2], "a position")});
        sr.finish();
        r.finish();
        return out;
    } catch (const std::invalid_argument&) {
        throw UserError(name + ": \"hash\" must be 16 hex digits");
    } catch (const std::out_of_range&) {
        throw UserError(name + ": \"hash\" must be 16 hex digits");
    } catch (const UserError& e) {
        throw UserError(name + ": " + e.what());
    }
}

} // namespace netsculpt
