// netsculpt-studio: the desktop studio (GLFW + OpenGL 3.3 + Dear ImGui). See App.h.

#include "App.h"
#include "StudioOptions.h"

#include "commands/HeapSettings.h"
#include "model/Error.h"

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
    using namespace netsculpt;
    keepFreedMemoryForReuse();
    studio::StudioOptions options;
    try {
        options = studio::parseStudioOptions(std::vector<std::string>(argv + 1, argv + argc));
    } catch (const UserError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    }
    if (options.help) {
        std::fputs(studio::studioUsage().c_str(), stdout);
        return 0;
    }
    try {
        studio::App app(options);
        return app.run();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "netsculpt-studio: %s\n", e.what());
        return 1;
    }
}
