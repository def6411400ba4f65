#pragma once
// The time limit of a test's relaxation whose outcome is decided by convergence or a step limit:
// only a guard against a hang. Such runs take about a second in Release, but tens of seconds in
// the sanitized debug build on a busy machine, where limits of 10-60 s ran out.

namespace netsculpt::test {

inline constexpr double kHangGuardSeconds = 900;

} // namespace netsculpt::test
