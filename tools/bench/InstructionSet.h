#pragma once
// The vector instructions this build was compiled for (CMakeLists.txt's NETSCULPT_NATIVE). Every
// benchmark prints it with its figures, which depend on it.

namespace netsculpt::bench {

constexpr const char* instructionSet() {
#if defined(__AVX512F__)
    return "x86-64-v4 (AVX-512)";
#elif defined(__AVX2__)
    return "x86-64-v3 (AVX2)";
#else
    return "x86-64 (SSE2)";
#endif
}

} // namespace netsculpt::bench
