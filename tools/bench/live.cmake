# netsculpt-bench-live: the studio's live preview after an edit at 20k knots, without a window
# (a plain program, not a test). Included from tools/bench/CMakeLists.txt.
# Run: netsculpt-bench-live [--knots N] [--steps N] [--backend NAME]
add_executable(netsculpt-bench-live ${CMAKE_CURRENT_LIST_DIR}/live_bench.cpp)
target_link_libraries(netsculpt-bench-live PRIVATE netsculpt_bench_scenes)
