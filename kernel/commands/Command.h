#pragma once
// Every change to a sculpture is one of these commands (DESIGN.md "Journal"). A command is
// plain typed data: it is validated and applied by applyCommand(), recorded in the journal by
// name with its arguments, and undone exactly (the document keeps the state before it).

#include "model/Edits.h"

#include <string>
#include <variant>
#include <vector>

namespace netsculpt {

struct NamedCurve {
    std::string name;
    CurveSpec curve;
};

struct AddRailCommand { std::string name; CurveSpec curve; };
/// Rails read from a file; the journal keeps the curves themselves so that a replay does not
/// depend on the file still being there.
struct ImportRailsCommand { std::string source; std::vector<NamedCurve> rails; };
struct RemoveRailCommand { RailId rail; };
struct RenameRailCommand { RailId rail; std::string name; };
struct AttachToRailCommand { AttachToRailArgs args; };
struct AttachToPieceCommand { AttachToPieceArgs args; };
struct SplitCommand { PieceId piece; int column = 0; };
struct SetRowsCommand { PieceId piece; int rows = 1; };
struct SetColumnsCommand { PieceId piece; int columns = 2; };
struct SetGearCommand { PieceId piece; Gear gear; };
/// By column (column 0 or the last; empty = the whole piece) or, when row is set, by row.
struct SetBarLengthCommand { PieceId piece; std::optional<int> column; std::optional<int> row; double length = 0.25; };
struct ConnectToRailCommand { PieceId piece; RailId rail; double at = 0; bool reverse = false; };
struct DisconnectCommand { PieceId piece; };
struct SetMaterialCommand { PieceId piece; Material material; };
struct SetColourCommand { PieceId piece; Colour colour; };
struct RenamePieceCommand { PieceId piece; std::string name; };
/// Removes the piece and everything hanging below it (one undo step).
struct RemovePieceCommand { PieceId piece; };
struct SetGravityCommand { Vec3 gravity; };

using Command = std::variant<AddRailCommand, ImportRailsCommand, RemoveRailCommand, RenameRailCommand,
                             AttachToRailCommand, AttachToPieceCommand, SplitCommand, SetRowsCommand,
                             SetColumnsCommand, SetGearCommand, SetBarLengthCommand, ConnectToRailCommand,
                             DisconnectCommand, SetMaterialCommand, SetColourCommand, RenamePieceCommand,
                             RemovePieceCommand, SetGravityCommand>;

/// The ids a command created (checked on replay).
struct CommandResult {
    std::vector<RailId> rails;
    std::vector<PieceId> pieces;
    bool operator==(const CommandResult&) const = default;
};

/// The journal / Lua name of a command: "add_rail", "attach_to_rail", "split", ...
std::string commandName(const Command& command);

/// Applies the command to `s` (a working copy). Throws UserError; `s` may then be half-changed,
/// which is why callers work on a copy.
CommandResult applyCommand(Sculpture& s, const Command& command);

/// Whether `next` may merge into `previous` as one undo step (a continuous gesture): the same
/// kind of command on the same piece, of a kind that sets a value (rows, columns, gear, bar length).
bool canMerge(const Command& previous, const Command& next);

} // namespace netsculpt
