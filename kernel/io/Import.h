#pragma once
// Rails from files (DESIGN.md "Rails"; issue: rails from CAD files): DXF (through dxflib),
// OBJ polylines ("l" elements) and CSV (x,y,z rows; one rail per file or a `rail` column; a
// spreadsheet's UTF-8 byte-order mark before the first field is skipped).
//
// Units. DXF files say their unit in the header variable $INSUNITS; it is converted to metres.
// A DXF whose $INSUNITS is 0 (unitless) or missing is refused with a message asking for units,
// unless ImportOptions::units names one; a code that is not a DXF unit (e.g. 99) is refused
// always. When the file states a unit and ImportOptions::units names a different one, that is
// refused too (the file wins only when nobody contradicts it). OBJ and CSV carry no units: they
// are read as metres unless ImportOptions::units says otherwise.
//
// Closed rails. DXF: the entity's closed flag (a chain of LINEs and ARCs is closed when its
// ends meet). OBJ and CSV: a rail whose last point repeats its first point is closed (the
// repeated point is dropped); exportRailsFile writes closed rails that way.
//
// Names. DXF: "LAYER:HANDLE" of the entity (of the first entity of a LINE/ARC chain, in file
// order; "LAYER:#N" for the N-th entity when the file has no handles). OBJ: the name of the `o`
// or `g` the line belongs to (else the file's stem), with "#k" appended when it holds several
// lines. CSV: the `rail` column's value (else the file's stem).

#include "commands/Command.h"

#include <filesystem>
#include <string>
#include <vector>

namespace netsculpt {

struct ImportOptions {
    /// Length unit of the file's numbers when the file does not say ("" = the rules above):
    /// one of unitNames() — "m", "mm", "cm", "dm", "km", "in", "ft", "yd", "mi".
    std::string units;
};

/// Reads every rail of a file, chosen by extension (.dxf, .obj, .csv; case-insensitive), in
/// metres. Throws UserError naming the file, the line or entity and the reason; never returns a
/// partial result. Each rail is checked with Curve::build.
std::vector<NamedCurve> importRailsFile(const std::filesystem::path& path);
std::vector<NamedCurve> importRailsFile(const std::filesystem::path& path,
                                        const ImportOptions& options);

/// The unit names ImportOptions::units accepts.
std::vector<std::string> unitNames();
/// Metres per unit of a unit name; UserError listing unitNames() for an unknown one.
double metresPerUnit(const std::string& unit);

} // namespace netsculpt
