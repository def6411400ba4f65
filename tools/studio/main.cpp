// netsculpt-studio: the desktop studio (GLFW + OpenGL 3.3 + Dear ImGui). See App.h.

#include "App.h"
#include "StudioOptions.h"

#include "commands/HeapSettings.h"

#include <cstdio>
#include <exception>
#include <iostream>

int main(int argc, char** argv) {
    using namespace netsculpt;
    keepFreedMemoryForReuse();
    const studio::CommandLine commandLine =
        studio::readCommandLine({argv + 1, argv + argc}, std::cout, std::cerr);
    if (commandLine.exitStatus)
        return *commandLine.exitStatus;
    try {
        studio::App app(commandLine.options);
        return app.run();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "netsculpt-studio: %s\n", e.what());
        return 1;
    }
}
