#pragma once
// A fixed scene and camera for the interaction tests, and helpers that drive the interaction
// layer with the same events a window would send (move, press, release, key).

#include "interaction/Interaction.h"
#include "model/TestSculptures.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <unistd.h>

namespace netsculpt::test {

/// The fixed camera every test looks through: 1000 x 800 px, looking at (0, 0, 1.5) from the
/// front-left and above.
inline Camera fixedCamera() {
    Camera camera(1000, 800);
    camera.target = {0, 0, 1.5};
    camera.distance = 12;
    camera.yaw = -2.1;
    camera.pitch = 0.3;
    camera.sceneRadius = 4;
    return camera;
}

/// A piece of `rows` x `columns` with bars `bar` m long hung from `rail` (an attach command).
inline PieceId attachPiece(Document& doc, RailId rail, int columns, int rows, double bar) {
    AttachToRailArgs args;
    args.rail = rail;
    args.columns = columns;
    args.rows = rows;
    args.bar = bar;
    return doc.execute(AttachToRailCommand{args}).pieces.front();
}

/// Rails: 1 "crown" (closed, r = 2, z = 3), 2 "ring" (closed, r = 0.8, z = 0), 3 "beam" (open,
/// 2 m long at z = 3.5 beside the crown). Piece 1 hangs from the crown: 24 columns, 6 rows, bar 0.35.
struct Scene {
    Document doc;
    Camera camera = fixedCamera();
    RailId crown, ring, beam;
    PieceId net;

    Scene() {
        crown = doc.execute(AddRailCommand{"crown", polygonRail(24, 2.0, 3.0)}).rails.front();
        ring = doc.execute(AddRailCommand{"ring", polygonRail(24, 0.8, 0.0)}).rails.front();
        beam = doc.execute(AddRailCommand{"beam", lineRail({2.5, -1, 3.5}, {2.5, 1, 3.5})}).rails.front();
        net = attachPiece(doc, crown, 24, 6, 0.35);
        doc.endGesture();
    }
};

/// Where a world point shows on the fixed camera (must be on screen).
inline ScreenPoint onScreen(const Camera& camera, const Vec3& p) {
    const ScreenPoint sp = camera.project(p);
    REQUIRE(sp.visible);
    return sp;
}

inline void moveTo(Interaction& ui, double x, double y) { ui.handle(MouseMove{x, y}); }

/// Press on the handle's sphere and release without moving.
inline void clickHandle(Interaction& ui, const Handle& h) {
    const ScreenPoint sp = onScreen(ui.camera(), h.position);
    moveTo(ui, sp.x, sp.y);
    ui.handle(MousePress{MouseButton::Left, {}});
    ui.handle(MouseRelease{MouseButton::Left, {}});
}

/// Press on the handle, move by (0, dy) in steps of at most 4 px, release.
inline void dragHandle(Interaction& ui, const Handle& h, double dy) {
    const ScreenPoint sp = onScreen(ui.camera(), h.position);
    moveTo(ui, sp.x, sp.y);
    ui.handle(MousePress{MouseButton::Left, {}});
    const int n = std::max(1, int(std::ceil(std::abs(dy) / 4)));
    for (int i = 1; i <= n; ++i) moveTo(ui, sp.x, sp.y + dy * i / n);
    ui.handle(MouseRelease{MouseButton::Left, {}});
}

/// The first handle of `ui` that matches pred (fails the test when none does).
template <typename Pred> Handle findHandle(const Interaction& ui, Pred pred) {
    for (const Handle& h : ui.handles())
        if (pred(h)) return h;
    FAIL("no handle matches");
    return {};
}

/// A fresh path in the temp folder, removed when the object goes.
struct TempFile {
    std::filesystem::path path;
    explicit TempFile(const std::string& name)
        : path(std::filesystem::temp_directory_path() /
               ("netsculpt-interaction-" + std::to_string(::getpid()) + "-" + name)) {
        std::filesystem::remove(path);
    }
    ~TempFile() { std::filesystem::remove(path); }
};

} // namespace netsculpt::test
