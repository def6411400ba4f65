#include "commands/JsonCodec.h"

#include "model/Error.h"

#include <type_traits>

namespace netsculpt::codec {

// ---- commands ----

Json commandArgs(const Command& command) {
    Json j = Json::object();
    std::visit(
        [&](const auto& c) {
            using T = std::decay_t<decltype(c)>;
            if constexpr (std::is_same_v<T, AddRailCommand>) {
                j["name"] = c.name;
                j.update(curveJson(c.curve));
            } else if constexpr (std::is_same_v<T, ImportRailsCommand>) {
                j["source"] = c.source;
                Json rails = Json::array();
                for (const NamedCurve& rail : c.rails) {
                    Json one = Json::object();
                    one["name"] = rail.name;
                    one.update(curveJson(rail.curve));
                    rails.push_back(std::move(one));
                }
                j["rails"] = std::move(rails);
            } else if constexpr (std::is_same_v<T, RemoveRailCommand>) {
                j["rail"] = c.rail.value;
            } else if constexpr (std::is_same_v<T, RenameRailCommand>) {
                j["rail"] = c.rail.value;
                j["name"] = c.name;
            } else if constexpr (std::is_same_v<T, AttachToRailCommand>) {
                const AttachToRailArgs& a = c.args;
                j["rail"] = a.rail.value;
                if (a.columns != 0 || a.spacing == 0) j["columns"] = a.columns;
                if (a.spacing != 0) j["spacing"] = number(a.spacing, "spacing");
                j["rows"] = a.rows;
                j["bar"] = number(a.bar, "bar");
                j["at"] = number(a.at, "at");
                j["reverse"] = a.reverse;
            } else if constexpr (std::is_same_v<T, AttachToPieceCommand>) {
                j["piece"] = c.args.parent.value;
                j["gear"] = gearText(c.args.gear);
                j["rows"] = c.args.rows;
                j["bar"] = number(c.args.bar, "bar");
                // Written only when given: entries without one replay with the default rope.
                if (c.args.material)
                    j["material"] = materialJson(*c.args.material, Json::object());
            } else if constexpr (std::is_same_v<T, SplitCommand>) {
                j["piece"] = c.piece.value;
                j["column"] = c.column;
            } else if constexpr (std::is_same_v<T, SetRowsCommand>) {
                j["piece"] = c.piece.value;
                j["rows"] = c.rows;
            } else if constexpr (std::is_same_v<T, SetColumnsCommand>) {
                j["piece"] = c.piece.value;
                j["columns"] = c.columns;
            } else if constexpr (std::is_same_v<T, SetGearCommand>) {
                j["piece"] = c.piece.value;
                j["gear"] = gearText(c.gear);
            } else if constexpr (std::is_same_v<T, SetBarLengthCommand>) {
                j["piece"] = c.piece.value;
                if (c.column) j["column"] = *c.column;
                if (c.row) j["row"] = *c.row;
                j["length"] = number(c.length, "length");
            } else if constexpr (std::is_same_v<T, ConnectToRailCommand>) {
                j["piece"] = c.piece.value;
                j["rail"] = c.rail.value;
                j["at"] = number(c.at, "at");
                j["reverse"] = c.reverse;
            } else if constexpr (std::is_same_v<T, DisconnectCommand> || std::is_same_v<T, RemovePieceCommand>) {
                j["piece"] = c.piece.value;
            } else if constexpr (std::is_same_v<T, SetMaterialCommand>) {
                j["piece"] = c.piece.value;
                j = materialJson(c.material, std::move(j));
            } else if constexpr (std::is_same_v<T, SetColourCommand>) {
                j["piece"] = c.piece.value;
                j["colour"] = colourJson(c.colour);
            } else if constexpr (std::is_same_v<T, RenamePieceCommand>) {
                j["piece"] = c.piece.value;
                j["name"] = c.name;
            } else {
                static_assert(std::is_same_v<T, SetGravityCommand>);
                j["gravity"] = vec3Json(c.gravity, "gravity");
            }
        },
        command);
    return j;
}

Command decodeCommand(const std::string& name, const Json& args) {
    ObjectReader r(args, name + " arguments");
    Command out;
    const auto piece = [&](const char* key = "piece") { return PieceId(r.id(key)); };
    const auto rail = [&](const char* key = "rail") { return RailId(r.id(key)); };
    if (name == "add_rail") {
        AddRailCommand c;
        c.name = r.text("name");
        c.curve = readCurve(r);
        out = std::move(c);
    } else if (name == "import_rails") {
        ImportRailsCommand c;
        c.source = r.text("source");
        const Json& rails = r.raw("rails");
        if (!rails.is_array()) throw UserError("import_rails: \"rails\" must be an array");
        for (const Json& one : rails) {
            ObjectReader rr(one, "import_rails rail");
            NamedCurve nc{rr.text("name"), readCurve(rr)};
            rr.finish();
            c.rails.push_back(std::move(nc));
        }
        out = std::move(c);
    } else if (name == "remove_rail") {
        out = RemoveRailCommand{rail()};
    } else if (name == "rename_rail") {
        out = RenameRailCommand{rail(), r.text("name")};
    } else if (name == "attach_to_rail") {
        AttachToRailArgs a;
        a.rail = rail();
        if (r.has("columns")) a.columns = r.integer("columns");
        if (r.has("spacing")) a.spacing = r.real("spacing");
        a.rows = r.integer("rows");
        a.bar = r.real("bar");
        a.at = r.real("at");
        a.reverse = r.boolean("reverse");
        out = AttachToRailCommand{a};
    } else if (name == "attach_to_piece") {
        AttachToPieceArgs a;
        a.parent = piece();
        a.gear = gearFromText(r.text("gear"), name);
        a.rows = r.integer("rows");
        a.bar = r.real("bar");
        if (r.has("material")) {
            ObjectReader m(r.raw("material"), "attach_to_piece material");
            a.material = readMaterial(m);
            m.finish();
        }
        out = AttachToPieceCommand{a};
    } else if (name == "split") {
        const PieceId p = piece();
        out = SplitCommand{p, r.integer("column")};
    } else if (name == "set_rows") {
        const PieceId p = piece();
        out = SetRowsCommand{p, r.integer("rows")};
    } else if (name == "set_columns") {
        const PieceId p = piece();
        out = SetColumnsCommand{p, r.integer("columns")};
    } else if (name == "set_gear") {
        const PieceId p = piece();
        out = SetGearCommand{p, gearFromText(r.text("gear"), name)};
    } else if (name == "set_bar_length") {
        SetBarLengthCommand c;
        c.piece = piece();
        if (r.has("column")) c.column = r.integer("column");
        if (r.has("row")) c.row = r.integer("row");
        c.length = r.real("length");
        out = c;
    } else if (name == "connect_to_rail") {
        ConnectToRailCommand c;
        c.piece = piece();
        c.rail = rail();
        c.at = r.real("at");
        c.reverse = r.boolean("reverse");
        out = c;
    } else if (name == "disconnect") {
        out = DisconnectCommand{piece()};
    } else if (name == "set_material") {
        const PieceId p = piece();
        out = SetMaterialCommand{p, readMaterial(r)};
    } else if (name == "set_colour") {
        const PieceId p = piece();
        out = SetColourCommand{p, readColour(r, "colour")};
    } else if (name == "rename_piece") {
        const PieceId p = piece();
        out = RenamePieceCommand{p, r.text("name")};
    } else if (name == "remove_piece") {
        out = RemovePieceCommand{piece()};
    } else if (name == "set_gravity") {
        out = SetGravityCommand{r.vec3("gravity")};
    } else {
        throw UserError("unknown command \"" + name + "\"");
    }
    r.finish();
    return out;
}

// ---- journal entries ----

Json entryObject(const JournalEntry& entry) {
    Json j = Json::object();
    j["seq"] = entry.seq;
    switch (entry.kind) {
    case JournalEntry::Kind::Undo: j["cmd"] = "undo"; break;
    case JournalEntry::Kind::Redo: j["cmd"] = "redo"; break;
    case JournalEntry::Kind::Command: {
        j["cmd"] = commandName(entry.command);
        j["args"] = commandArgs(entry.command);
        if (!entry.created.rails.empty() || !entry.created.pieces.empty()) {
            Json created = Json::object();
            if (!entry.created.rails.empty()) {
                Json ids = Json::array();
                for (RailId id : entry.created.rails) ids.push_back(id.value);
                created["rails"] = std::move(ids);
            }
            if (!entry.created.pieces.empty()) {
                Json ids = Json::array();
                for (PieceId id : entry.created.pieces) ids.push_back(id.value);
                created["pieces"] = std::move(ids);
            }
            j["created"] = std::move(created);
        }
        if (entry.merge) j["merge"] = true;
        break;
    }
    }
    return j;
}

JournalEntry decodeEntryObject(const Json& object) {
    ObjectReader r(object, "entry");
    JournalEntry entry;
    entry.seq = r.unsignedInteger("seq");
    const std::string cmd = r.text("cmd");
    if (cmd == "undo" || cmd == "redo") {
        entry.kind = cmd == "undo" ? JournalEntry::Kind::Undo : JournalEntry::Kind::Redo;
        r.finish();
        return entry;
    }
    entry.command = decodeCommand(cmd, r.raw("args"));
    if (r.has("created")) {
        ObjectReader cr(r.raw("created"), cmd + " \"created\"");
        for (const char* key : {"rails", "pieces"}) {
            if (!cr.has(key)) continue;
            const Json& ids = cr.raw(key);
            if (!ids.is_array()) throw UserError(cmd + ": created " + key + " must be an array of ids");
            for (const Json& id : ids) {
                if (!id.is_number_unsigned() || id.get<std::uint64_t>() > 0xffffffffu)
                    throw UserError(cmd + ": created " + key + " must be an array of ids, got " + id.dump());
                if (key[0] == 'r') entry.created.rails.push_back(RailId(id.get<std::uint32_t>()));
                else entry.created.pieces.push_back(PieceId(id.get<std::uint32_t>()));
            }
        }
        cr.finish();
    }
    if (r.has("merge")) entry.merge = r.boolean("merge");
    r.finish();
    return entry;
}

} // namespace netsculpt::codec
