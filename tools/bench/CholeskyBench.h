#pragma once
// The fast path's linear algebra alone (netsculpt-bench-fast --scene cholesky): one numeric
// factorization and one solve of SupernodalCholesky on a tube's Newton-matrix pattern.

namespace netsculpt::bench {

/// Prints, for tubes of 20k and 100k knots (20k only when quick), the factor's size and flops
/// and the best wall time of a factorization and of a solve with one thread and with two.
void choleskyTimes(bool quick);

} // namespace netsculpt::bench
