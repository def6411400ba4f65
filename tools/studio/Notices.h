#pragma once
// What the status line says after a file action. An export of a shape that is not the
// equilibrium at the material's stiffness (a soft preview, the initial geometry, a refine still
// running) says so, since its forces are not the net's; an opened design or a restored session
// shows the warnings reading it gave (a torn last entry dropped) with the outcome.

#include <string>
#include <vector>

namespace netsculpt::studio {

struct Notice {
    std::string text;
    bool error = false; ///< shown in the error colour
};

/// The notice for an export to `path`. `relaxed`: the document's shape is an equilibrium at the
/// material's stiffness. `previewScale` < 1: the shape is the soft preview's, relaxed at that
/// fraction of the material's stiffness (1 = not a preview).
Notice exportNotice(const std::string& path, bool relaxed, double previewScale);

/// The notice after a design was opened or a session restored: `done` ("opened PATH") and, in
/// the error colour, the `warnings` of reading it, which the status line shows with it.
Notice openNotice(const std::string& done, const std::vector<std::string>& warnings);

} // namespace netsculpt::studio
