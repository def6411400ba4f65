#include "BenchScenes.h"

#include "model/Compiler.h"
#include "model/ReferenceSculptures.h"

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

} // namespace netsculpt::bench
