// The window-free camera: projection agrees with the matrices the renderer uses, rays go back
// through the pixels they came from, framing keeps the whole box in view, and mouse gestures move it.

#include "InteractionTestSupport.h"

using namespace netsculpt;
using namespace netsculpt::test;

namespace {

/// Pixel of p through the view and projection matrices (what the GPU does).
std::array<double, 2> throughMatrices(const Camera& c, const Vec3& p) {
    const Mat4 m = c.projection() * c.view();
    double clip[4];
    for (int r = 0; r < 4; ++r) clip[r] = m(r, 0) * p.x + m(r, 1) * p.y + m(r, 2) * p.z + m(r, 3);
    return {(clip[0] / clip[3] + 1) * 0.5 * c.width(), (1 - clip[1] / clip[3]) * 0.5 * c.height()};
}

/// Pixel of p through the matrices as the renderer hands them to the GPU: floats, the point given
/// from `origin` and the view taken from there (Camera::view(origin)).
std::array<double, 2> throughFloatMatrices(const Camera& c, const Vec3& origin, const Vec3& p) {
    const std::array<float, 16> m = (c.projection() * c.view(origin)).toFloat();
    const Vec3 d = p - origin;
    const float v[4] = {float(d.x), float(d.y), float(d.z), 1.0f};
    float clip[4];
    for (int r = 0; r < 4; ++r) {
        clip[r] = 0;
        for (int k = 0; k < 4; ++k) clip[r] += m[std::size_t(k * 4 + r)] * v[k];
    }
    return {(clip[0] / clip[3] + 1) * 0.5 * c.width(), (1 - clip[1] / clip[3]) * 0.5 * c.height()};
}

} // namespace

TEST_CASE("camera: a sculpture in site coordinates, drawn in floats from its origin, lands where "
          "it is",
          "[camera]") {
    const Vec3 site{512345.678, 5412345.678, 231.5}, origin{512346, 5412346, 232};
    Camera c = fixedCamera();
    c.target = site;
    double fromOrigin = 0, fromZero = 0;
    for (const Vec3 offset : {Vec3{1, 2, 3}, Vec3{-2, 0.5, 0}, Vec3{0.3, -1.7, 2.2}}) {
        const Vec3 p = site + offset;
        const ScreenPoint sp = c.project(p);
        REQUIRE(sp.visible);
        const auto a = throughFloatMatrices(c, origin, p), b = throughFloatMatrices(c, {}, p);
        fromOrigin = std::max({fromOrigin, std::abs(a[0] - sp.x), std::abs(a[1] - sp.y)});
        fromZero = std::max({fromZero, std::abs(b[0] - sp.x), std::abs(b[1] - sp.y)});
    }
    CHECK(fromOrigin < 0.01); // pixels: 2e-5 measured
    CHECK(fromZero > 2); // floats of the site's own coordinates, 0.5 m apart there: 12 px measured
}

TEST_CASE("camera: project agrees with view x projection and rayAt inverts it", "[camera]") {
    Camera c = fixedCamera();
    const ScreenPoint centre = c.project(c.target);
    CHECK(centre.x == Approx(500));
    CHECK(centre.y == Approx(400));
    CHECK(centre.depth == Approx(12));
    for (const Vec3 p : {Vec3{1, 2, 3}, Vec3{-2, 0.5, 0}, Vec3{0.3, -1.7, 2.2}}) {
        const ScreenPoint sp = c.project(p);
        REQUIRE(sp.visible);
        const auto m = throughMatrices(c, p);
        CHECK(sp.x == Approx(m[0]).margin(1e-9));
        CHECK(sp.y == Approx(m[1]).margin(1e-9));
        const Ray ray = c.rayAt(sp.x, sp.y);
        const Vec3 back = ray.origin + ray.direction * (p - ray.origin).norm();
        CHECK(distance(back, p) < 1e-9);
    }
    // z is up on screen: a point above the target is higher on screen (smaller y).
    CHECK(c.project(c.target + Vec3{0, 0, 1}).y < 400);
    // One pixel at the target's depth covers 2 d tan(fov/2) / height metres.
    CHECK(c.worldPerPixels(c.target, 1) == Approx(2 * 12 * std::tan(c.fovY / 2) / 800));
    CHECK_FALSE(c.project(c.eye() - c.forward()).visible); // behind the eye
}

TEST_CASE("camera: frame keeps the box in view, presets look along the axes", "[camera]") {
    Camera c(640, 480);
    const Vec3 lo{-3, -1, 0}, hi{2, 4, 6};
    for (ViewPreset preset : {ViewPreset::Perspective, ViewPreset::Top, ViewPreset::Front, ViewPreset::Side}) {
        c.setPreset(preset);
        c.frame(lo, hi);
        for (int i = 0; i < 8; ++i) {
            const Vec3 corner{i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z};
            CHECK(c.project(corner).visible);
        }
    }
    c.setPreset(ViewPreset::Top);
    CHECK(c.forward().z == Approx(-1).margin(1e-5));
    CHECK(c.project(c.target + Vec3{0, 1, 0}).y < c.project(c.target).y); // +y up on screen
    c.setPreset(ViewPreset::Front);
    CHECK(c.forward().y == Approx(1));
    CHECK(c.project(c.target + Vec3{1, 0, 0}).x > c.project(c.target).x); // +x to the right
    c.setPreset(ViewPreset::Side);
    CHECK(c.forward().x == Approx(-1));
}

TEST_CASE("camera: frame keeps the box clear of the insets at the window's sides", "[camera]") {
    Camera c(1280, 800);
    c.frameInset = 320;
    const Vec3 lo{-10, -1, 0}, hi{10, 1, 4}; // wide: the width decides the distance
    c.frame(lo, hi);
    double left = 1280, right = 0;
    for (int i = 0; i < 8; ++i) {
        const Vec3 corner{i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z};
        left = std::min(left, c.project(corner).x);
        right = std::max(right, c.project(corner).x);
    }
    CHECK(left >= 320);
    CHECK(right <= 1280 - 320);
    CHECK(right - left > 0.5 * (1280 - 2 * 320)); // and still fills the space between them
    // A window too narrow for the insets frames across its whole width.
    Camera narrow(600, 800);
    narrow.frameInset = 320;
    narrow.frame(lo, hi);
    CHECK(narrow.project(lo).visible);
    CHECK(narrow.project(hi).visible);
}

TEST_CASE("camera: drags orbit and pan, the wheel zooms, keys choose views", "[camera]") {
    Scene scene;
    Interaction ui(scene.doc, scene.camera);
    const double yaw = scene.camera.yaw, distance = scene.camera.distance;
    moveTo(ui, 900, 700); // empty space
    ui.handle(MousePress{MouseButton::Left, {}});
    moveTo(ui, 950, 700);
    ui.handle(MouseRelease{MouseButton::Left, {}});
    CHECK(scene.camera.yaw == Approx(yaw - 50 * 0.007));

    // A pan drag keeps the point under the cursor under the cursor.
    const Vec3 target = scene.camera.target;
    ui.handle(MousePress{MouseButton::Right, {}});
    moveTo(ui, 900, 650);
    ui.handle(MouseRelease{MouseButton::Right, {}});
    CHECK(onScreen(scene.camera, target).x == Approx(500 - 50).margin(1e-6));
    CHECK(onScreen(scene.camera, target).y == Approx(400 - 50).margin(1e-6));

    ui.handle(Scroll{2});
    CHECK(scene.camera.distance == Approx(distance * 0.85 * 0.85));
    ui.handle(KeyPress{'T', {}});
    CHECK(scene.camera.forward().z < -0.99);
    ui.handle(KeyPress{keys::Home, {}});
    const auto [lo, hi] = sceneBounds(scene.doc.sculpture(), scene.doc.compiled());
    CHECK(onScreen(scene.camera, lo).visible);
    CHECK(onScreen(scene.camera, hi).visible);
    CHECK(scene.doc.hash() == Scene().doc.hash()); // the camera never changes the sculpture
}
