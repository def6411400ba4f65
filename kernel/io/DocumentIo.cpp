// The Document forms of the report and export: what the document knows about its shape, passed
// to the sculpture-level functions. Kept apart so that programs using only the sculpture-level
// functions do not link the document.

#include "io/Export.h"
#include "io/Report.h"

#include <nlohmann/json.hpp>

namespace netsculpt {

RelaxStatus relaxStatus(const Document& doc) {
    RelaxStatus status;
    status.relaxed = doc.isRelaxed();
    status.last = doc.lastRelax();
    status.wind = doc.shapeWind();
    status.tolerance = doc.shapeTolerance() > 0 ? doc.shapeTolerance() : RelaxOptions{}.tolerance;
    return status;
}

nlohmann::json buildReport(const Document& doc) {
    return buildReport(doc.sculpture(), doc.compiled(), relaxStatus(doc));
}

void exportFile(const Document& doc, const std::filesystem::path& path,
                const ExportOptions& options) {
    exportFile(doc.sculpture(), doc.compiled(), relaxStatus(doc), path, options);
}

} // namespace netsculpt
