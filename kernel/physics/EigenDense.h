#pragma once
// Eigen's dense module, as netsculpt includes it. Built for x86-64-v4 (AVX-512), GCC 12 reports
// -Wmaybe-uninitialized falsely inside its own intrinsics header (avx512fintrin.h, a variable
// initialized from itself on purpose) wherever Eigen's products are instantiated; the warning is
// silenced for those headers' text only, so netsculpt's own code keeps it. Include this before
// anything that includes <immintrin.h>.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <Eigen/Dense>
#pragma GCC diagnostic pop
