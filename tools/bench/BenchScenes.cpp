#include "BenchScenes.h"

#include "model/Compiler.h"
#include "model/ReferenceSculptures.h"

#include <algorithm>

namespace netsculpt::bench {

Material realisticRope() {
    return Material{2e5, 0.01, 0.002, 0.006};
}

MassSpringSystem tubeOnCircularRail(int rows, int columns, const Material& material) {
    return compileSculpture(netsculpt::tubeOnCircularRail(rows, columns, material)).system;
}

MassSpringSystem sheetBetweenParallelRails(int rows, int columns, const Material& material) {
    return compileSculpture(netsculpt::sheetBetweenParallelRails(rows, columns, material)).system;
}

MassSpringSystem bannerOnWavyRail(int rows, int columns, const Material& material) {
    return compileSculpture(netsculpt::bannerOnWavyRail(rows, columns, material)).system;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double largestDistance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    double largest = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        largest = std::max(largest, distance(a[i], b[i]));
    return largest;
}

} // namespace netsculpt::bench
