#include "commands/Command.h"

#include "model/Error.h"

#include <type_traits>

namespace netsculpt {

namespace {

template <typename T> constexpr const char* nameOf() {
    if constexpr (std::is_same_v<T, AddRailCommand>) return "add_rail";
    else if constexpr (std::is_same_v<T, ImportRailsCommand>) return "import_rails";
    else if constexpr (std::is_same_v<T, RemoveRailCommand>) return "remove_rail";
    else if constexpr (std::is_same_v<T, RenameRailCommand>) return "rename_rail";
    else if constexpr (std::is_same_v<T, AttachToRailCommand>) return "attach_to_rail";
    else if constexpr (std::is_same_v<T, AttachToPieceCommand>) return "attach_to_piece";
    else if constexpr (std::is_same_v<T, SplitCommand>) return "split";
    else if constexpr (std::is_same_v<T, SetRowsCommand>) return "set_rows";
    else if constexpr (std::is_same_v<T, SetColumnsCommand>) return "set_columns";
    else if constexpr (std::is_same_v<T, SetGearCommand>) return "set_gear";
    else if constexpr (std::is_same_v<T, SetBarLengthCommand>) return "set_bar_length";
    else if constexpr (std::is_same_v<T, ConnectToRailCommand>) return "connect_to_rail";
    else if constexpr (std::is_same_v<T, DisconnectCommand>) return "disconnect";
    else if constexpr (std::is_same_v<T, SetMaterialCommand>) return "set_material";
    else if constexpr (std::is_same_v<T, SetColourCommand>) return "set_colour";
    else if constexpr (std::is_same_v<T, RenamePieceCommand>) return "rename_piece";
    else if constexpr (std::is_same_v<T, RemovePieceCommand>) return "remove_piece";
    else {
        static_assert(std::is_same_v<T, SetGravityCommand>, "every command kind has a name");
        return "set_gravity";
    }
}

/// The piece a value-setting command acts on (for merging), or null.
PieceId mergeTarget(const Command& c) {
    return std::visit(
        [](const auto& cmd) -> PieceId {
            using T = std::decay_t<decltype(cmd)>;
            if constexpr (std::is_same_v<T, SetRowsCommand> || std::is_same_v<T, SetColumnsCommand> ||
                          std::is_same_v<T, SetGearCommand> || std::is_same_v<T, SetBarLengthCommand>)
                return cmd.piece;
            else
                return PieceId{};
        },
        c);
}

} // namespace

std::string commandName(const Command& command) {
    return std::visit([](const auto& cmd) { return std::string(nameOf<std::decay_t<decltype(cmd)>>()); }, command);
}

CommandResult applyCommand(Sculpture& s, const Command& command) {
    CommandResult result;
    std::visit(
        [&](const auto& c) {
            using T = std::decay_t<decltype(c)>;
            if constexpr (std::is_same_v<T, AddRailCommand>) {
                result.rails.push_back(addRail(s, c.name, c.curve));
            } else if constexpr (std::is_same_v<T, ImportRailsCommand>) {
                if (c.rails.empty())
                    throw UserError("import_rails: \"" + c.source + "\" holds no rails (polylines or curves)");
                for (const NamedCurve& rail : c.rails) result.rails.push_back(addRail(s, rail.name, rail.curve));
            } else if constexpr (std::is_same_v<T, RemoveRailCommand>) {
                removeRail(s, c.rail);
            } else if constexpr (std::is_same_v<T, RenameRailCommand>) {
                renameRail(s, c.rail, c.name);
            } else if constexpr (std::is_same_v<T, AttachToRailCommand>) {
                result.pieces.push_back(attachToRail(s, c.args));
            } else if constexpr (std::is_same_v<T, AttachToPieceCommand>) {
                result.pieces.push_back(attachToPiece(s, c.args));
            } else if constexpr (std::is_same_v<T, SplitCommand>) {
                const auto [left, right] = split(s, c.piece, c.column); // left keeps the piece's id
                result.pieces = {left, right};
            } else if constexpr (std::is_same_v<T, SetRowsCommand>) {
                setRows(s, c.piece, c.rows);
            } else if constexpr (std::is_same_v<T, SetColumnsCommand>) {
                setColumns(s, c.piece, c.columns);
            } else if constexpr (std::is_same_v<T, SetGearCommand>) {
                setGear(s, c.piece, c.gear);
            } else if constexpr (std::is_same_v<T, SetBarLengthCommand>) {
                if (c.column && c.row)
                    throw UserError("set_bar_length: give column or row, not both (column " +
                                    std::to_string(*c.column) + ", row " + std::to_string(*c.row) + ")");
                if (c.row) setBarLengthByRow(s, c.piece, *c.row, c.length);
                else setBarLength(s, c.piece, c.column, c.length);
            } else if constexpr (std::is_same_v<T, ConnectToRailCommand>) {
                connectToRail(s, c.piece, c.rail, c.at, c.reverse);
            } else if constexpr (std::is_same_v<T, DisconnectCommand>) {
                disconnect(s, c.piece);
            } else if constexpr (std::is_same_v<T, SetMaterialCommand>) {
                setMaterial(s, c.piece, c.material);
            } else if constexpr (std::is_same_v<T, SetColourCommand>) {
                setColour(s, c.piece, c.colour);
            } else if constexpr (std::is_same_v<T, RenamePieceCommand>) {
                renamePiece(s, c.piece, c.name);
            } else if constexpr (std::is_same_v<T, RemovePieceCommand>) {
                removePiece(s, c.piece);
            } else {
                static_assert(std::is_same_v<T, SetGravityCommand>);
                setGravity(s, c.gravity);
            }
        },
        command);
    return result;
}

bool canMerge(const Command& previous, const Command& next) {
    if (previous.index() != next.index()) return false;
    const PieceId target = mergeTarget(previous);
    return target && target == mergeTarget(next);
}

} // namespace netsculpt
