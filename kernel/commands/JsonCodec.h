#pragma once
// Internal to kernel/commands: the JSON form of commands and of the model, shared by the
// journal and the snapshot. Keys are the Lua API's argument names (DESIGN.md "Lua API").
// Every double is written with round-trip precision (nlohmann's Grisu2: the shortest text that
// reads back to the same bits); a non-finite double is refused (UserError), never written.
// Readers are strict: a missing, mistyped or unknown key is a UserError naming the key.

#include "commands/Command.h"
#include "commands/Journal.h"

#include <nlohmann/json.hpp>

#include <set>
#include <string_view>
#include <string>

namespace netsculpt::codec {

using Json = nlohmann::ordered_json;

/// The deepest nesting of arrays and objects that parseJson accepts (our files nest 8 levels).
inline constexpr int kMaxJsonNesting = 100;

/// Parses JSON text; UserError("bad JSON: ...") for malformed text, for a number that no
/// double holds (1e400) and for nesting deeper than kMaxJsonNesting, so a damaged file is
/// reported like any other damage.
Json parseJson(std::string_view text);

/// A finite double as JSON; UserError naming `what` for NaN or infinity.
Json number(double value, const char* what);

/// Reads the members of one JSON object, checking types and ranges; finish() refuses members
/// that nothing read (so a misspelt key is an error, not silently ignored).
class ObjectReader {
  public:
    ObjectReader(const Json& object, std::string what);
    bool has(const char* key) const;
    const Json& raw(const char* key);
    int integer(const char* key);
    std::uint32_t id(const char* key);
    std::uint64_t unsignedInteger(const char* key);
    double real(const char* key);
    bool boolean(const char* key);
    std::string text(const char* key);
    Vec3 vec3(const char* key);
    void finish() const;

  private:
    const Json& object_;
    std::string what_;
    std::set<std::string> read_;
    [[noreturn]] void fail(const char* key, const std::string& expected) const;
};

double realValue(const Json& value, const std::string& what);
Vec3 vec3Value(const Json& value, const std::string& what);
Json vec3Json(const Vec3& v, const char* what);

/// The command's arguments (the "args" object of a journal entry).
Json commandArgs(const Command& command);
/// A command from its journal name and arguments; UserError for an unknown name or bad args.
Command decodeCommand(const std::string& name, const Json& args);

/// "2", "1/2"; the reader takes "n" or "n/d" (whether the gear is allowed is the edit's check).
std::string gearText(Gear g);
Gear gearFromText(const std::string& text, const std::string& what);
/// Adds stiffness, compression_ratio, knot_mass, linear_density, and breaking_load when the
/// material has one, to `j`.
Json materialJson(const Material& m, Json j);
Material readMaterial(ObjectReader& r);
Json colourJson(const Colour& c);
Colour readColour(ObjectReader& r, const char* key);

Json curveJson(const CurveSpec& spec);
/// Reads the curve members (points|control, degree, knots, weights, closed, sampling) from `r`.
CurveSpec readCurve(ObjectReader& r);

/// The whole model (rails with their curve specs, pieces with every field, seams, id counters,
/// gravity), for snapshots.
Json sculptureJson(const Sculpture& s);
/// A journal entry as a JSON object: {"seq", "cmd", "args", "created", "merge"}.
Json entryObject(const JournalEntry& entry);
/// The entry of a JSON object (line left 0); UserError for anything malformed.
JournalEntry decodeEntryObject(const Json& object);
Sculpture decodeSculpture(const Json& model);

} // namespace netsculpt::codec
