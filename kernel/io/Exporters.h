#pragma once
// The writers behind exportFile, one per format; each returns the file's bytes (exportFile
// writes them atomically). Internal to kernel/io.

#include "io/Export.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace netsculpt::io {

struct ExportInput {
    const Sculpture& sculpture;
    const CompiledSculpture& compiled;
    const RelaxStatus& status;
    const ExportOptions& options;
};

std::string knotsCsv(const ExportInput& in);
std::string objText(const ExportInput& in);
std::string plyText(const ExportInput& in);
std::string glbBytes(const ExportInput& in);
std::string jsonDocument(const ExportInput& in);
std::string svgText(const ExportInput& in);
std::string pngBytes(const ExportInput& in);

/// A triangle mesh of tubes around segments.
struct TubeMesh {
    std::vector<Vec3> vertices;
    std::vector<Vec3> normals;
    std::vector<std::array<std::uint32_t, 3>> triangles;
};
inline constexpr int kTubeSides = 8;
/// Appends an open tube of `radius` around a-b: kTubeSides vertices at each end, 2 kTubeSides
/// triangles (none for a zero-length segment).
void appendTube(TubeMesh& mesh, const Vec3& a, const Vec3& b, double radius);

} // namespace netsculpt::io
