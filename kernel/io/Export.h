#pragma once
// Geometry, pictures and documents out (by the file's extension): csv (knots, DESIGN.md format),
// obj and ply (knots and bars as lines, or bars as tubes), glb (glTF 2.0 binary, bars coloured by
// tension), json (rails, pieces, knots, bars, report), svg and png (views of the net), dxf (bars as
// LINEs on a layer per piece, rails as 3D POLYLINEs; DxfExport.h).
//
// Every number written as text has round-trip precision (the shortest form that reads back to
// the same double), except SVG drawing coordinates (pixels, rounded to 1/100). glb stores
// positions as 32-bit floats (glTF requires it), in netsculpt's frame (z up) under a root node
// that turns it to glTF's y up. Colours: piece colours are linear RGB; png/svg convert them to
// sRGB, glb keeps them linear.

#include "commands/Document.h"
#include "io/Report.h"

#include <filesystem>
#include <string>
#include <vector>

namespace netsculpt {

struct ExportOptions {
    std::string colourBy = "piece"; ///< "piece" or "tension"
    double tubeRadius = 0; ///< m; obj/ply/glb: 0 = bars as lines, > 0 = bars as tube meshes
    int width = 1600;      ///< png: pixels (16 to 16384); svg: its nominal size
    int height = 1200;     ///< png: pixels (16 to 16384)
    /// svg/png: "top", "side", "front", "perspective", or "all" (the four in a 2x2 sheet)
    std::string view = "all";
};

/// The extensions exportFile understands: "csv", "obj", "ply", "glb", "json", "svg", "png", "dxf".
std::vector<std::string> exportFormats();
/// Throws the UserError exportFile throws for `path`'s extension and for bad options, before any
/// work is done (the CLI checks its files before it relaxes).
void checkExport(const std::filesystem::path& path, const ExportOptions& options);

/// Writes the document's current (relaxed, if relaxed) shape to `path`, format by extension.
/// Writes to a temporary file beside it and renames, so a failure leaves no half-written file.
/// Throws UserError for an unknown extension (listing the valid ones), bad options, or I/O errors.
void exportFile(const Document& doc, const std::filesystem::path& path,
                const ExportOptions& options = {});
/// The same for a sculpture and its compiled system at its current positions.
void exportFile(const Sculpture& sculpture, const CompiledSculpture& compiled,
                const RelaxStatus& status, const std::filesystem::path& path,
                const ExportOptions& options = {});

/// The extensions exportRailsFile understands: "csv", "obj", "dxf".
std::vector<std::string> railExportFormats();
/// Throws the UserError exportRailsFile throws for `path`'s extension, before any work is done.
void checkRailsExport(const std::filesystem::path& path);

/// Writes the rails alone, by extension: .csv (header rail,x,y,z; one row per point), .obj
/// (one `o` and one `l` polyline per rail) or .dxf (one 3D POLYLINE per rail carrying its name,
/// DxfExport.h). A polyline rail is written as its vertices, a spline rail as 64 points per knot
/// span (at least 256) at equal parameter steps; a closed rail repeats its first point at the end
/// in .csv and .obj, and is flagged closed in .dxf. importRailsFile reads all three back to the
/// same names, closure and points (bit for bit).
void exportRailsFile(const Sculpture& sculpture, const std::filesystem::path& path);

} // namespace netsculpt
