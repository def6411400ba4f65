# netsculpt-bench-fast: the "fast" (Newton) relaxation against RK4 at a rope's real stiffness
# (a plain program, not a test). Included from tools/bench/CMakeLists.txt.
# Run: netsculpt-bench-fast [--quick] [--threads N] [--rk4-cap S] [--no-rk4] [--scene NAME]
add_executable(netsculpt-bench-fast ${CMAKE_CURRENT_LIST_DIR}/fast_bench.cpp
  ${CMAKE_CURRENT_LIST_DIR}/CholeskyBench.cpp)
target_link_libraries(netsculpt-bench-fast PRIVATE netsculpt_bench_scenes)
