#pragma once
// What the status line says after File > Export: the studio exports the shape it shows, and an
// export of a shape that is not the equilibrium at the material's stiffness (a soft preview, the
// initial geometry, a refine still running) says so, since its forces are not the net's.

#include <string>

namespace netsculpt::studio {

struct Notice {
    std::string text;
    bool error = false; ///< shown in the error colour
};

/// The notice for an export to `path`. `relaxed`: the document's shape is an equilibrium at the
/// material's stiffness. `previewScale` < 1: the shape is the soft preview's, relaxed at that
/// fraction of the material's stiffness (1 = not a preview).
Notice exportNotice(const std::string& path, bool relaxed, double previewScale);

} // namespace netsculpt::studio
