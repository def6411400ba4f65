# netsculpt-bench-compare: the bullet, rk4 and fast relaxations side by side on the same nets at
# about 2k, 20k and 200k knots (a plain program, not a test). Included from
# tools/bench/CMakeLists.txt only when NETSCULPT_WITH_BULLET is on.
# Run: netsculpt-bench-compare [--quick] [--sizes 0.2k,2k,20k,200k] [--cap S] [--threads N]
add_executable(netsculpt-bench-compare ${CMAKE_CURRENT_LIST_DIR}/bullet_compare.cpp)
target_link_libraries(netsculpt-bench-compare PRIVATE netsculpt_bench_scenes)
