#pragma once
// DXF out (Export.h): an ASCII DXF of AutoCAD Release 12 (AC1009) with $INSUNITS = 6 (metres),
// z up, in the sculpture's coordinates (site coordinates as they are), every number in the
// shortest text that reads back to the same double. Internal to kernel/io.
//
// Layers: "piece_<id>_<name>" per piece and "rail_<id>_<name>" per rail, the name's characters
// other than ASCII letters, digits, '-' and '_' replaced by '_' (what every DXF version allows
// in a layer name), its length cut so that the layer name has at most 255 characters; a default
// name ("piece 3" of piece 3) or none gives "piece_3".
// Colours (ACI): a piece's layer the ACI hue and shade nearest its colour (8 for a grey), the
// rails' 7 (black or white, by the CAD program's background).
//
// Entities: each bar a LINE from knot to knot; each rail a 3D POLYLINE (flag 8, and 1 when
// closed; a closed rail does not repeat its first vertex) of the points exportRailsFile writes.
// netsculpt's marks ride in extended data of application NETSCULPT: a rail's POLYLINE carries
// "rail" and the rail's exact name, a bar's LINE "bar". importRailsFile names a rail after its
// mark and leaves marked bars out, so a drawing netsculpt wrote gives its rails back.

#include "model/Compiler.h"
#include "model/Sculpture.h"

#include <string>

namespace netsculpt::io {

/// A DXF layer name for `kind` ("piece", "rail"), `id` and a user's `name` (rules above).
std::string dxfLayerName(const std::string& kind, int id, const std::string& name);
/// The ACI colour number nearest an sRGB colour (rules above).
int nearestAci(double r, double g, double b);

/// The drawing: the rails, and when `system` is given, every bar of every piece.
std::string dxfText(const Sculpture& sculpture, const MassSpringSystem* system);

} // namespace netsculpt::io
