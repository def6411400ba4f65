#pragma once
// Built-in sculptures for the studio's --demo (until scripts can be run) and for its tests:
// every one is built through Document::execute, so it lands in the journal like an artist's work.

#include "commands/Document.h"

namespace netsculpt {

/// A crown rail with a net, a geared net below it drawn in to a small ring, and a sheet on an
/// open rail beside them (three pieces, three rails; about 1000 knots).
void buildDemoSculpture(Document& doc);

/// One closed rail with one tube of about `knots` knots (for frame-rate measurements).
void buildLargeDemoSculpture(Document& doc, int knots);

/// One sheet of about `knots` knots (twice as many columns as rows) on a straight rail, its last
/// row tied to a second, parallel rail nearer than the sheet's height, so that it hangs slack
/// between the two (the paper's Fig. 11 kind of join; for the live preview's measurements).
/// tied = false: the second rail is there ("bottom") but the sheet hangs from the first alone.
void buildLargeSlackSheet(Document& doc, int knots, bool tied = true);

} // namespace netsculpt
