// Catch2 runner for the studio's window tests: they need an X server, which xvfb-run provides.
// Without xvfb-run the program says so and exits with 77, which ctest reports as skipped.

#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) {
        std::puts("SKIPPED: xvfb-run is not installed (apt install xvfb); the studio's window tests need it");
        return 77;
    }
    return Catch::Session().run(argc, argv);
}
