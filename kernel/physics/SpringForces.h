#pragma once
// The spring force of one bar (Eq. 3), and of four or eight bars at once in SIMD lanes, as the
// force pass (Forces.cpp) computes it: the scalar and the SIMD code perform the same IEEE
// operations in the same order, so a force comes out with the same bits whichever computes it
// (and so on any number of threads). Internal to kernel/physics; compiled without contracted
// multiply-adds (-ffp-contract=off, see CMakeLists.txt) in the files that include it.

#include "geometry/Vec3.h"

#include <cmath>
#include <cstdint>

#if defined(__AVX2__)
// GCC 12 reports -Wmaybe-uninitialized falsely inside avx512fintrin.h (see EigenDense.h).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#endif

namespace netsculpt::springs {

/// |d|^2 as the rest of the kernel computes it (Vec3::norm() as g++ contracts it where FMA is
/// available): the same bits here, in the SIMD lanes below and in a caller's own distance().
inline double squaredLength(const Vec3& d) {
#if defined(__FMA__)
    return std::fma(d.z, d.z, std::fma(d.x, d.x, d.y * d.y));
#else
    return d.x * d.x + d.y * d.y + d.z * d.z;
#endif
}

/// The spring force of a bar on its end a (Eq. 3): c d, d = p_b - p_a, c = t / |d| with the
/// tension t = s k (|d| - l_eq) (k = kTension if stretched, else kCompression), and c = 0 for a
/// bar of zero length. The SIMD code below performs exactly these IEEE operations in this order.
struct SpringForce {
    Vec3 force;
    double tension; ///< N
};
inline SpringForce springForce(const Vec3& pa, const Vec3& pb, double restLength, double kTension,
                               double kCompression, double scale) {
    const Vec3 d{pb.x - pa.x, pb.y - pa.y, pb.z - pa.z};
    const double length = std::sqrt(squaredLength(d));
    const double extension = length - restLength;
    const double t = (extension > 0 ? kTension : kCompression) * scale * extension;
    const double c = length > 0 ? t / length : 0.0;
    return {Vec3{d.x * c, d.y * c, d.z * c}, t};
}

/// The Vec3 at a byte offset into an array of them (bars keep their ends as byte offsets: an
/// address is then one addition, in scalar and in SIMD code alike).
inline const Vec3& at(const Vec3* array, std::uint32_t offset) {
    return *reinterpret_cast<const Vec3*>(reinterpret_cast<const char*>(array) + offset);
}
inline Vec3& at(Vec3* array, std::uint32_t offset) {
    return *reinterpret_cast<Vec3*>(reinterpret_cast<char*>(array) + offset);
}

inline void addTo(Vec3& total, const Vec3& f) {
    total.x += f.x;
    total.y += f.y;
    total.z += f.z;
}
inline void subtractFrom(Vec3& total, const Vec3& f) {
    total.x -= f.x;
    total.y -= f.y;
    total.z -= f.z;
}

#if defined(__AVX2__)
/// springForce() of four bars at once, as (x, y) and z of each bar's force on its end a.
struct SpringForces4 {
    __m128d xy[4];
    __m128d z[4];
    __m256d tension;
};
/// (x, y, z, next x) of a position, or (x, y, z, 0) if Masked (for the array's last one).
template <bool Masked> inline __m256d loadVec3(const Vec3& v) {
    const Vec3* p = &v;
    if constexpr (Masked)
        return _mm256_maskload_pd(&p->x, _mm256_set_epi64x(0, -1, -1, -1));
    else
        return _mm256_loadu_pd(&p->x);
}
/// Masked: some bar may end at the last knot (a plain 32-byte load would read past the array).
template <bool Masked>
inline SpringForces4 springForces4(const Vec3* positions, const std::uint32_t* endOffsets,
                                   const double* restLength, const double* kTension,
                                   const double* kCompression, __m256d scale) {
    __m256d d[4]; // (x, y, z, _) of p_b - p_a; the fourth lane is never used
    for (int i = 0; i < 4; ++i)
        d[i] = _mm256_sub_pd(loadVec3<Masked>(at(positions, endOffsets[2 * i + 1])),
                             loadVec3<Masked>(at(positions, endOffsets[2 * i])));
    // Transpose to x, y, z of the four bars.
    const __m256d t0 = _mm256_unpacklo_pd(d[0], d[1]), t1 = _mm256_unpackhi_pd(d[0], d[1]);
    const __m256d t2 = _mm256_unpacklo_pd(d[2], d[3]), t3 = _mm256_unpackhi_pd(d[2], d[3]);
    const __m256d x = _mm256_permute2f128_pd(t0, t2, 0x20),
                  z = _mm256_permute2f128_pd(t0, t2, 0x31);
    const __m256d y = _mm256_permute2f128_pd(t1, t3, 0x20);
    const __m256d zero = _mm256_setzero_pd();
#if defined(__FMA__)
    const __m256d squared = _mm256_fmadd_pd(z, z, _mm256_fmadd_pd(x, x, _mm256_mul_pd(y, y)));
#else
    const __m256d squared =
        _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(x, x), _mm256_mul_pd(y, y)), _mm256_mul_pd(z, z));
#endif
    const __m256d length = _mm256_sqrt_pd(squared);
    const __m256d extension = _mm256_sub_pd(length, _mm256_loadu_pd(restLength));
    const __m256d k = _mm256_blendv_pd(_mm256_loadu_pd(kCompression), _mm256_loadu_pd(kTension),
                                       _mm256_cmp_pd(extension, zero, _CMP_GT_OQ));
    SpringForces4 out;
    out.tension = _mm256_mul_pd(_mm256_mul_pd(k, scale), extension);
    const __m256d c =
        _mm256_and_pd(_mm256_div_pd(out.tension, length), _mm256_cmp_pd(length, zero, _CMP_GT_OQ));
    const __m256d fx = _mm256_mul_pd(x, c), fy = _mm256_mul_pd(y, c), fz = _mm256_mul_pd(z, c);
    const __m256d xy02 = _mm256_unpacklo_pd(fx, fy), xy13 = _mm256_unpackhi_pd(fx, fy);
    out.xy[0] = _mm256_castpd256_pd128(xy02);
    out.xy[1] = _mm256_castpd256_pd128(xy13);
    out.xy[2] = _mm256_extractf128_pd(xy02, 1);
    out.xy[3] = _mm256_extractf128_pd(xy13, 1);
    const __m128d z01 = _mm256_castpd256_pd128(fz), z23 = _mm256_extractf128_pd(fz, 1);
    out.z[0] = z01;
    out.z[1] = _mm_unpackhi_pd(z01, z01);
    out.z[2] = z23;
    out.z[3] = _mm_unpackhi_pd(z23, z23);
    return out;
}
#if defined(__AVX512F__) && defined(__FMA__)
/// springForce() of eight bars at once, lane by lane the same IEEE operations as springForces4
/// (an AVX-512 square root or division of eight lanes takes as long as AVX2's of four on this
/// project's machines: the force pass 1.45 -> 1.37 ns per bar with two threads).
struct SpringForces8 {
    __m128d xy[8];
    __m128d z[8];
};
/// Bars 2 Lane and 2 Lane + 1 of the 128-bit lane Lane of the force vectors (Lane 1-3).
template <int Lane>
inline void takeLanes(SpringForces8& out, __m512d xyEven, __m512d xyOdd, __m512d zEven,
                      __m512d zOdd) {
    out.xy[2 * Lane] = _mm512_extractf64x2_pd(xyEven, Lane);
    out.xy[2 * Lane + 1] = _mm512_extractf64x2_pd(xyOdd, Lane);
    out.z[2 * Lane] = _mm512_extractf64x2_pd(zEven, Lane);
    out.z[2 * Lane + 1] = _mm512_extractf64x2_pd(zOdd, Lane);
}
/// (x, y, z, _) of p_b - p_a of bar i in the low half of a lane pair, of bar i + 4 in the high.
template <bool Masked>
inline __m512d barVectors(const Vec3* positions, const std::uint32_t* endOffsets, int i) {
    auto difference = [&](int bar) {
        return _mm256_sub_pd(loadVec3<Masked>(at(positions, endOffsets[2 * bar + 1])),
                             loadVec3<Masked>(at(positions, endOffsets[2 * bar])));
    };
    return _mm512_insertf64x4(_mm512_castpd256_pd512(difference(i)), difference(i + 4), 1);
}
template <bool Masked>
inline SpringForces8 springForces8(const Vec3* positions, const std::uint32_t* endOffsets,
                                   const double* restLength, const double* kTension,
                                   const double* kCompression, __m512d scale) {
    __m512d d[4];
    for (int i = 0; i < 4; ++i)
        d[i] = barVectors<Masked>(positions, endOffsets, i);
    // Transpose to x, y, z of the eight bars in bar order: t0 = (x0 x1 z0 z1 | x4 x5 z4 z5),
    // t2 = (x2 x3 z2 z3 | x6 x7 z6 z7), t1 and t3 the same with y.
    const __m512d t0 = _mm512_unpacklo_pd(d[0], d[1]), t1 = _mm512_unpackhi_pd(d[0], d[1]);
    const __m512d t2 = _mm512_unpacklo_pd(d[2], d[3]), t3 = _mm512_unpackhi_pd(d[2], d[3]);
    const __m512i first = _mm512_setr_epi64(0, 1, 8, 9, 4, 5, 12, 13);
    const __m512i second = _mm512_setr_epi64(2, 3, 10, 11, 6, 7, 14, 15);
    const __m512d x = _mm512_permutex2var_pd(t0, first, t2);
    const __m512d y = _mm512_permutex2var_pd(t1, first, t3);
    const __m512d z = _mm512_permutex2var_pd(t0, second, t2);
    const __m512d zero = _mm512_setzero_pd();
    const __m512d squared = _mm512_fmadd_pd(z, z, _mm512_fmadd_pd(x, x, _mm512_mul_pd(y, y)));
    const __m512d length = _mm512_sqrt_pd(squared);
    const __m512d extension = _mm512_sub_pd(length, _mm512_loadu_pd(restLength));
    const __m512d k = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(extension, zero, _CMP_GT_OQ),
                                           _mm512_loadu_pd(kCompression),
                                           _mm512_loadu_pd(kTension));
    const __m512d tension = _mm512_mul_pd(_mm512_mul_pd(k, scale), extension);
    const __m512d c =
        _mm512_maskz_div_pd(_mm512_cmp_pd_mask(length, zero, _CMP_GT_OQ), tension, length);
    const __m512d fx = _mm512_mul_pd(x, c), fy = _mm512_mul_pd(y, c), fz = _mm512_mul_pd(z, c);
    // (x, y) of bars 0 2 4 6 and 1 3 5 7; z of bars 0 2 4 6 in fz's even lanes, 1 3 5 7 in zOdd's.
    const __m512d xyEven = _mm512_unpacklo_pd(fx, fy), xyOdd = _mm512_unpackhi_pd(fx, fy);
    const __m512d zOdd = _mm512_unpackhi_pd(fz, fz);
    SpringForces8 out;
    out.xy[0] = _mm512_castpd512_pd128(xyEven);
    out.xy[1] = _mm512_castpd512_pd128(xyOdd);
    out.z[0] = _mm512_castpd512_pd128(fz);
    out.z[1] = _mm512_castpd512_pd128(zOdd);
    takeLanes<1>(out, xyEven, xyOdd, fz, zOdd);
    takeLanes<2>(out, xyEven, xyOdd, fz, zOdd);
    takeLanes<3>(out, xyEven, xyOdd, fz, zOdd);
    return out;
}
#endif
inline void addTo(Vec3& total, __m128d xy, __m128d z) {
    // f + total: the same bits as total + f, and the load folds into the addition.
    _mm_storeu_pd(&total.x, _mm_add_pd(xy, _mm_loadu_pd(&total.x)));
    _mm_store_sd(&total.z, _mm_add_sd(z, _mm_load_sd(&total.z)));
}
inline void subtractFrom(Vec3& total, __m128d xy, __m128d z) {
    _mm_storeu_pd(&total.x, _mm_sub_pd(_mm_loadu_pd(&total.x), xy));
    _mm_store_sd(&total.z, _mm_sub_sd(_mm_load_sd(&total.z), z));
}
#endif

} // namespace netsculpt::springs
