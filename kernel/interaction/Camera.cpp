#include "interaction/Camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace netsculpt {

namespace {

constexpr double kMaxPitch = 89.9 * std::numbers::pi / 180;

Vec3 normalized(const Vec3& v) {
    const double n = v.norm();
    return n > 0 ? v / n : Vec3{};
}

} // namespace

Mat4 Mat4::identity() {
    Mat4 out;
    for (int i = 0; i < 4; ++i) out(i, i) = 1;
    return out;
}

Mat4 Mat4::operator*(const Mat4& o) const {
    Mat4 out;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
            double sum = 0;
            for (int k = 0; k < 4; ++k) sum += (*this)(r, k) * o(k, c);
            out(r, c) = sum;
        }
    return out;
}

std::array<float, 16> Mat4::toFloat() const {
    std::array<float, 16> out{};
    for (std::size_t i = 0; i < 16; ++i) out[i] = float(m[i]);
    return out;
}

void Camera::setViewport(int width, int height) {
    width_ = std::max(1, width);
    height_ = std::max(1, height);
}

Vec3 Camera::forward() const {
    return -Vec3{std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), std::sin(pitch)};
}

Vec3 Camera::eye() const { return target - forward() * distance; }

Vec3 Camera::right() const {
    // Horizontal even when looking straight down (yaw still orients the view).
    return Vec3{-std::sin(yaw), std::cos(yaw), 0};
}

Vec3 Camera::up() const { return normalized(right().cross(forward())); }

double Camera::nearPlane() const { return std::max(1e-3, std::max(distance - 2 * sceneRadius, distance * 0.01)); }

double Camera::farPlane() const { return distance + 4 * sceneRadius + 1; }

void Camera::orbit(double dxPixels, double dyPixels, double radiansPerPixel) {
    yaw -= dxPixels * radiansPerPixel;
    pitch = std::clamp(pitch + dyPixels * radiansPerPixel, -kMaxPitch, kMaxPitch);
}

void Camera::pan(double dxPixels, double dyPixels) {
    const double perPixel = worldPerPixels(target, 1);
    target += right() * (-dxPixels * perPixel) + up() * (dyPixels * perPixel);
}

void Camera::zoom(double steps) { distance = std::clamp(distance * std::pow(0.85, steps), 1e-3, 1e7); }

void Camera::frame(const Vec3& lo, const Vec3& hi) {
    target = (lo + hi) * 0.5;
    const double radius = std::max(0.5 * (hi - lo).norm(), 1e-3);
    sceneRadius = radius;
    const int inset = width_ - 2 * frameInset >= width_ / 3 ? frameInset : 0;
    const double aspect = double(width_ - 2 * inset) / height_;
    const double halfFov = 0.5 * std::min(fovY, 2 * std::atan(std::tan(0.5 * fovY) * aspect));
    distance = radius / std::sin(halfFov) * 1.02;
}

void Camera::setPreset(ViewPreset preset) {
    switch (preset) {
    case ViewPreset::Perspective: yaw = -2.1; pitch = 0.3; break;
    case ViewPreset::Top: yaw = -std::numbers::pi / 2; pitch = kMaxPitch; break;
    case ViewPreset::Front: yaw = -std::numbers::pi / 2; pitch = 0; break;
    case ViewPreset::Side: yaw = 0; pitch = 0; break;
    }
}

Mat4 Camera::view() const { return view(Vec3{}); }

Mat4 Camera::view(const Vec3& origin) const {
    const Vec3 f = forward(), r = right(), u = up(), e = eye() - origin;
    Mat4 v = Mat4::identity();
    v(0, 0) = r.x, v(0, 1) = r.y, v(0, 2) = r.z, v(0, 3) = -r.dot(e);
    v(1, 0) = u.x, v(1, 1) = u.y, v(1, 2) = u.z, v(1, 3) = -u.dot(e);
    v(2, 0) = -f.x, v(2, 1) = -f.y, v(2, 2) = -f.z, v(2, 3) = f.dot(e);
    return v;
}

Mat4 Camera::projection() const {
    const double n = nearPlane(), f = farPlane();
    const double t = 1 / std::tan(0.5 * fovY);
    const double aspect = double(width_) / height_;
    Mat4 p;
    p(0, 0) = t / aspect;
    p(1, 1) = t;
    p(2, 2) = -(f + n) / (f - n);
    p(2, 3) = -2 * f * n / (f - n);
    p(3, 2) = -1;
    return p;
}

ScreenPoint Camera::project(const Vec3& world) const {
    const Vec3 d = world - eye();
    ScreenPoint out;
    out.depth = d.dot(forward());
    if (out.depth <= 1e-12) return out;
    const double t = std::tan(0.5 * fovY);
    const double aspect = double(width_) / height_;
    const double ndcX = d.dot(right()) / (out.depth * t * aspect);
    const double ndcY = d.dot(up()) / (out.depth * t);
    out.x = (ndcX + 1) * 0.5 * width_;
    out.y = (1 - ndcY) * 0.5 * height_;
    out.visible = out.depth >= nearPlane() && out.x >= 0 && out.x <= width_ && out.y >= 0 && out.y <= height_;
    return out;
}

Ray Camera::rayAt(double x, double y) const {
    const double t = std::tan(0.5 * fovY);
    const double aspect = double(width_) / height_;
    const double ndcX = 2 * x / width_ - 1, ndcY = 1 - 2 * y / height_;
    const Vec3 direction = forward() + right() * (ndcX * t * aspect) + up() * (ndcY * t);
    return {eye(), normalized(direction)};
}

double Camera::worldPerPixels(const Vec3& at, double pixels) const {
    const double depth = std::max((at - eye()).dot(forward()), nearPlane());
    return pixels * 2 * depth * std::tan(0.5 * fovY) / height_;
}

} // namespace netsculpt
