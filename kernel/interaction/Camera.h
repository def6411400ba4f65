#pragma once
// The studio's orbit camera, window-free: it turns world points into window pixels and pixels
// into rays, so picking can be tested without a window. z is up (DESIGN.md "Units and frame").
// Pixels: origin at the window's top-left corner, y down; pixel centres at half-integers are not
// special (a point projects to continuous coordinates).

#include "geometry/Vec3.h"

#include <array>

namespace netsculpt {

/// 4x4 matrix, column-major (OpenGL's layout): element (row r, column c) is m[c * 4 + r].
struct Mat4 {
    std::array<double, 16> m{};
    static Mat4 identity();
    double operator()(int row, int column) const { return m[std::size_t(column * 4 + row)]; }
    double& operator()(int row, int column) { return m[std::size_t(column * 4 + row)]; }
    Mat4 operator*(const Mat4& o) const;
    std::array<float, 16> toFloat() const;
};

/// Where a world point lands on screen.
struct ScreenPoint {
    double x = 0, y = 0;  ///< window pixels
    double depth = 0;     ///< distance in front of the eye along the view direction, m (< 0 = behind)
    bool visible = false; ///< in front of the near plane and inside the window
};

struct Ray {
    Vec3 origin;    ///< the eye
    Vec3 direction; ///< unit
};

enum class ViewPreset {
    Perspective, ///< three-quarter view from the front-left and above
    Top,         ///< looking down -z, +y up on screen
    Front,       ///< looking along +y (from -y)
    Side,        ///< looking along -x (from +x)
};

class Camera {
  public:
    Camera() = default;
    Camera(int width, int height) { setViewport(width, height); }

    /// Window size in pixels (at least 1 x 1).
    void setViewport(int width, int height);
    int width() const { return width_; }
    int height() const { return height_; }

    // ---- the orbit: the eye sits at `distance` from `target`, at `yaw` around z (radians,
    // 0 = on +x) and `pitch` above the horizontal (radians, within +-89.9 degrees) ----
    Vec3 target{0, 0, 0};
    double distance = 10;              ///< m, > 0
    double yaw = -2.1;                 ///< rad
    double pitch = 0.3;                ///< rad
    double fovY = 0.6981317007977318;  ///< vertical field of view, rad (40 degrees)
    double sceneRadius = 5;            ///< m; sets the near and far planes
    /// Pixels that frame() keeps clear at the window's left and right edges (the studio's
    /// panels), when the window is wide enough to leave a third of it.
    int frameInset = 0;

    /// Turns the view by a mouse drag of (dx, dy) pixels (drag right = the scene turns right).
    void orbit(double dxPixels, double dyPixels, double radiansPerPixel = 0.007);
    /// Moves the target so the point under the cursor follows a drag of (dx, dy) pixels.
    void pan(double dxPixels, double dyPixels);
    /// steps > 0 moves closer: distance *= 0.85^steps.
    void zoom(double steps);
    /// Centres the box [lo, hi] and backs off until all of it is in view, between frameInset
    /// pixels from the left and right edges, keeping yaw and pitch.
    void frame(const Vec3& lo, const Vec3& hi);
    /// Looks from a preset direction (keeps target and distance).
    void setPreset(ViewPreset preset);

    Vec3 eye() const;
    Vec3 forward() const; ///< unit, eye -> target
    Vec3 right() const;   ///< unit, screen +x
    Vec3 up() const;      ///< unit, screen up (-y in pixels)
    double nearPlane() const;
    double farPlane() const;

    Mat4 view() const;       ///< world -> eye
    /// (world - origin) -> eye: the view of points given from `origin`, as the studio hands
    /// floats to OpenGL (a sculpture in site coordinates would lose its knots' places in floats
    /// of its own coordinates, and the view's translation with them).
    Mat4 view(const Vec3& origin) const;
    Mat4 projection() const; ///< eye -> clip (OpenGL conventions, depth in [-1, 1])

    ScreenPoint project(const Vec3& world) const;
    /// The ray through window pixel (x, y).
    Ray rayAt(double x, double y) const;
    /// World length that covers `pixels` pixels at the depth of `at` (for spheres of a pixel size).
    double worldPerPixels(const Vec3& at, double pixels) const;

  private:
    int width_ = 1280, height_ = 800;
};

} // namespace netsculpt
