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
// Closed rails. A rail whose end lies on its start (within 1e-6 of its extent) is closed and the
// repeated point dropped, in every format: a DXF polyline flagged closed or not, a chain of
// LINEs and ARCs, OBJ and CSV points; exportRailsFile writes closed rails that way.
//
// Chains. The LINEs and ARCs of a DXF layer and the `l` elements of an OBJ object are joined end
// to end (Chains.h); a piece shorter than the join tolerance is left out and the ends meeting it
// joined directly. DXF pieces join only within model space or within one block reference: never
// a piece of model space with one drawn through an INSERT, nor pieces of two INSERTs.
//
// DXF blocks and layers. INSERTs of model space are read through their transform (DxfBlocks.h).
// Entities on frozen or off layers and on Defpoints are not read, unless ImportOptions::layers
// lists the layers to read. Text is decoded to UTF-8 (DxfText.h). Coordinates beyond
// kMaxCoordinate (ImportDetail.h) are refused in every format.
//
// netsculpt's own DXF (DxfExport.h): a rail whose entity carries netsculpt's mark is named by
// it; a LINE marked as a bar is not read.
//
// Names. DXF: "LAYER:HANDLE" of the entity (of the first entity of a LINE/ARC chain, in file
// order; "LAYER:#N" for the N-th entity when the file has no handles); in a block reference
// "INSLAYER:INSHANDLE/BLOCK:HANDLE". OBJ: the name of the `o` or `g` the line belongs to (else
// the file's stem), with "#k" appended when it holds several rails. CSV: the `rail` column's
// value (else the file's stem).

#include "commands/Command.h"

#include <filesystem>
#include <string>
#include <vector>

namespace netsculpt {

struct ImportOptions {
    /// Length unit of the file's numbers when the file does not say ("" = the rules above):
    /// one of unitNames() — "m", "mm", "cm", "dm", "km", "in", "ft", "yd", "mi".
    std::string units;
    /// DXF only: the layers to read (compared without case; empty = every layer that is drawn).
    /// A name the drawing does not have is refused, with the drawing's layers.
    std::vector<std::string> layers;
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
