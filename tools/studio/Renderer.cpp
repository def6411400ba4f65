#include "Renderer.h"

#include "Shaders.h"

#include "interaction/Handles.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace netsculpt::studio {

namespace {

constexpr float kBackgroundTop[3] = {0.26f, 0.29f, 0.34f};
constexpr float kBackgroundBottom[3] = {0.07f, 0.08f, 0.10f};
constexpr float kFog[3] = {0.14f, 0.16f, 0.19f};
constexpr float kRailColour[4] = {0.78f, 0.80f, 0.84f, 1.0f};
constexpr std::size_t kMaxKnotDots = 5000; // knots; above this no dots (a software renderer pays per point)

GLuint compile(GLenum type, const char* source) {
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        throw std::runtime_error(std::string("studio shader does not compile: ") + log);
    }
    return shader;
}

GLuint link(const char* vertex, const char* fragment, const char* geometry = nullptr) {
    const GLuint program = glCreateProgram();
    const GLuint vs = compile(GL_VERTEX_SHADER, vertex), fs = compile(GL_FRAGMENT_SHADER, fragment);
    const GLuint gs = geometry ? compile(GL_GEOMETRY_SHADER, geometry) : 0;
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    if (gs) glAttachShader(program, gs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    if (gs) glDeleteShader(gs);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096] = {};
        glGetProgramInfoLog(program, sizeof log, nullptr, log);
        throw std::runtime_error(std::string("studio shader program does not link: ") + log);
    }
    return program;
}

GLint at(GLuint program, const char* name) { return glGetUniformLocation(program, name); }

void setMatrix(GLuint program, const char* name, const Mat4& m) {
    const auto f = m.toFloat();
    glUniformMatrix4fv(at(program, name), 1, GL_FALSE, f.data());
}

/// A vertex array of interleaved x y z r g b floats.
void makeColouredLines(GLuint& vao, GLuint& vbo) {
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &vbo);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
    glBindVertexArray(0);
}

void upload(GLuint vbo, const std::vector<float>& data) {
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size() * sizeof(float)), data.data(), GL_DYNAMIC_DRAW);
}

/// The colour at 6 bits a channel: bars whose keys differ are never drawn as one line.
std::uint32_t colourKey(const std::array<float, 3>& c) {
    auto level = [](float v) { return std::uint32_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 63)); };
    return level(c[0]) << 12 | level(c[1]) << 6 | level(c[2]);
}

} // namespace

/// Tension colour ramp: blue (low) - teal - yellow - red (the largest); slack bars grey.
std::array<float, 3> tensionColour(double tension, double maxTension) {
    if (!(tension > 0) || !(maxTension > 0)) return {0.42f, 0.44f, 0.50f};
    static constexpr float stops[4][3] = {{0.25f, 0.40f, 0.95f}, {0.15f, 0.80f, 0.70f}, {0.98f, 0.85f, 0.20f}, {0.95f, 0.22f, 0.12f}};
    const double x = std::clamp(tension / maxTension, 0.0, 1.0) * 3;
    const int i = std::min(2, int(x));
    const float f = float(x - i);
    return {stops[i][0] + (stops[i + 1][0] - stops[i][0]) * f, stops[i][1] + (stops[i + 1][1] - stops[i][1]) * f,
            stops[i][2] + (stops[i + 1][2] - stops[i][2]) * f};
}

Renderer::~Renderer() {
    const GLuint programs[] = {linesProgram_, thickProgram_, sphereProgram_, backgroundProgram_};
    for (GLuint p : programs)
        if (p) glDeleteProgram(p);
    const GLuint buffers[] = {barVbo_, knotVbo_, railVbo_, gridVbo_, guideVbo_, sphereQuadVbo_, sphereInstanceVbo_};
    glDeleteBuffers(GLsizei(std::size(buffers)), buffers);
    const GLuint arrays[] = {barVao_, knotVao_, railVao_, gridVao_, guideVao_, sphereVao_, emptyVao_};
    glDeleteVertexArrays(GLsizei(std::size(arrays)), arrays);
}

void Renderer::init() {
    linesProgram_ = link(shaders::kLinesVertex, shaders::kLinesFragment);
    thickProgram_ = link(shaders::kThickVertex, shaders::kThickFragment, shaders::kThickGeometry);
    sphereProgram_ = link(shaders::kSphereVertex, shaders::kSphereFragment);
    backgroundProgram_ = link(shaders::kBackgroundVertex, shaders::kBackgroundFragment);
    makeColouredLines(barVao_, barVbo_);
    makeColouredLines(knotVao_, knotVbo_);
    makeColouredLines(gridVao_, gridVbo_);
    makeColouredLines(guideVao_, guideVbo_);

    glGenVertexArrays(1, &railVao_);
    glGenBuffers(1, &railVbo_);
    glBindVertexArray(railVao_);
    glBindBuffer(GL_ARRAY_BUFFER, railVbo_);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);

    glGenVertexArrays(1, &sphereVao_);
    glGenBuffers(1, &sphereQuadVbo_);
    glGenBuffers(1, &sphereInstanceVbo_);
    glBindVertexArray(sphereVao_);
    const float corners[] = {-1, -1, 1, -1, -1, 1, 1, 1};
    glBindBuffer(GL_ARRAY_BUFFER, sphereQuadVbo_);
    glBufferData(GL_ARRAY_BUFFER, sizeof corners, corners, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), nullptr);
    glBindBuffer(GL_ARRAY_BUFFER, sphereInstanceVbo_);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, 8 * sizeof(float), nullptr);
    glVertexAttribDivisor(1, 1);
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, 8 * sizeof(float), reinterpret_cast<void*>(4 * sizeof(float)));
    glVertexAttribDivisor(2, 1);

    glGenVertexArrays(1, &emptyVao_);
    glBindVertexArray(0);
}

void Renderer::pushFromOrigin(std::vector<float>& out, const Vec3& p) const {
    const Vec3 d = p - renderOrigin_;
    out.insert(out.end(), {float(d.x), float(d.y), float(d.z)});
}

void Renderer::setSculpture(const Sculpture& s, const CompiledSculpture& compiled) {
    renderOrigin_ = compiled.system.origin;
    // Rails: dense samples as segments for the thick-line shader.
    std::vector<float> rails;
    for (const auto& [id, rail] : s.rails) {
        const Curve& curve = rail.curve();
        const int n = std::clamp(int(curve.length() / 0.02), 64, 4000);
        const int segments = curve.closed() ? n : n - 1;
        for (int i = 0; i < segments; ++i)
            for (int end = 0; end < 2; ++end) {
                const double t = curve.closed() ? double(i + end) / n : double(i + end) / (n - 1);
                const Vec3 p = curve.pointAt(curve.closed() ? std::fmod(t, 1.0) : t);
                pushFromOrigin(rails, p);
            }
    }
    glBindBuffer(GL_ARRAY_BUFFER, railVbo_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(rails.size() * sizeof(float)), rails.data(), GL_STATIC_DRAW);
    railVertices_ = GLsizei(rails.size() / 3);

    // Ground grid at z = 0, or just under the lowest point when the sculpture goes below it or
    // stands more than ten times its own size above it (a site's heights above sea level: a
    // floor that far down is not the sculpture's; an atrium's floor a few storeys down is).
    const auto [lo, hi] = sceneBounds(s, compiled);
    sceneRadius_ = float(std::max(0.5 * (hi - lo).norm(), 0.5));
    const double size = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1.0});
    const bool siteHeights = lo.z > 10 * size;
    const double floorZ = siteHeights ? lo.z - 0.05 : std::min(0.0, lo.z - 0.05);
    const double step = sceneRadius_ > 6 ? 1.0 : 0.5;
    const double half = std::ceil(std::max({hi.x - lo.x, hi.y - lo.y, 2.0}) * 0.75 / step) * step;
    const Vec3 c{std::round((lo.x + hi.x) / 2 / step) * step, std::round((lo.y + hi.y) / 2 / step) * step, floorZ};
    std::vector<float> grid;
    const float g = 0.42f;
    for (double d = -half; d <= half + 1e-9; d += step)
        for (const Vec3& p : {Vec3{c.x + d, c.y - half, floorZ}, Vec3{c.x + d, c.y + half, floorZ},
                              Vec3{c.x - half, c.y + d, floorZ},
                              Vec3{c.x + half, c.y + d, floorZ}}) {
            pushFromOrigin(grid, p);
            grid.insert(grid.end(), {g, g, g});
        }
    upload(gridVbo_, grid);
    gridVertices_ = GLsizei(grid.size() / 6);

    strands_ = buildStrands(compiled.system);
    barA_ = compiled.system.barA;
    barB_ = compiled.system.barB;
    barPiece_ = compiled.system.barPiece;
    linesStale_ = true;
}

void Renderer::setPositions(const Sculpture& s, const MassSpringSystem& sys, ColourBy colourBy) {
    if (barPiece_.size() != sys.barCount()) return; // setSculpture first
    std::vector<double> tension;
    maxTension_ = 0;
    if (colourBy == ColourBy::Tension) {
        tension.resize(sys.barCount());
        for (std::size_t b = 0; b < sys.barCount(); ++b) {
            const double l = distance(sys.position[sys.barA[b]], sys.position[sys.barB[b]]);
            const double strain = l - sys.restLength[b];
            tension[b] = strain > 0 ? sys.kTension[b] * strain : 0;
            maxTension_ = std::max(maxTension_, tension[b]);
        }
    }
    barColour_.resize(sys.barCount());
    barColourKey_.resize(sys.barCount());
    for (std::size_t b = 0; b < sys.barCount(); ++b) {
        if (colourBy == ColourBy::Tension) {
            barColour_[b] = tensionColour(tension[b], maxTension_);
        } else {
            const auto it = s.pieces.find(sys.barPiece[b]);
            const Colour c = it != s.pieces.end() ? it->second.colour : Colour{};
            barColour_[b] = {float(c.r), float(c.g), float(c.b)};
        }
        barColourKey_[b] = colourKey(barColour_[b]);
    }
    knotPositions_.resize(sys.knotCount());
    for (std::size_t k = 0; k < sys.knotCount(); ++k) knotPositions_[k] = sys.worldPosition(k);
    linesStale_ = true;
    uploadKnotDots();
}

void Renderer::uploadKnotDots() {
    knotDots_ = 0;
    if (knotPositions_.size() > kMaxKnotDots) return;
    std::vector<std::array<float, 3>> knotColour(knotPositions_.size(), {1, 1, 1});
    for (std::size_t b = 0; b < barColour_.size(); ++b) // a knot of two pieces takes the later one's colour
        for (std::uint32_t k : {barA_[b], barB_[b]}) knotColour[k] = barColour_[b];
    std::vector<float> data;
    data.reserve(knotPositions_.size() * 6);
    for (std::size_t k = 0; k < knotPositions_.size(); ++k) {
        const std::array<float, 3>& c = knotColour[k];
        pushFromOrigin(data, knotPositions_[k]);
        data.insert(data.end(), {c[0], c[1], c[2]});
    }
    upload(knotVbo_, data);
    knotDots_ = GLsizei(knotPositions_.size());
}

void Renderer::setBarMergeTolerance(double pixels) {
    barMergeTolerance_ = std::max(0.0, pixels);
    linesStale_ = true;
}

void Renderer::updateNetLines(const Camera& camera) {
    const bool merging = barMergeTolerance_ > 0;
    const std::array<float, 16> viewProjection =
        (camera.projection() * camera.view(renderOrigin_)).toFloat();
    const bool cameraMoved = viewProjection != linesViewProjection_ || camera.width() != linesWidth_ ||
                             camera.height() != linesHeight_;
    if (!linesStale_ && !(merging && cameraMoved)) return;
    linesStale_ = false;
    linesViewProjection_ = viewProjection;
    linesWidth_ = camera.width(), linesHeight_ = camera.height();

    if (merging) {
        NetLineOptions options;
        options.tolerancePixels = barMergeTolerance_;
        mergeStrands(strands_, projectKnots(knotPositions_, camera), barColourKey_, options, lines_);
    } else {
        strandBars(strands_, lines_);
    }
    uploadNetLines();
}

void Renderer::uploadNetLines() {
    barData_.resize(lines_.size() * 12);
    float* out = barData_.data();
    pieceRanges_.clear();
    for (std::size_t i = 0; i < lines_.size(); ++i) {
        const NetLine& line = lines_[i];
        const std::array<float, 3>& colour = barColour_[line.bar];
        for (std::uint32_t k : {line.a, line.b}) {
            const Vec3 p = knotPositions_[k] - renderOrigin_;
            *out++ = float(p.x), *out++ = float(p.y), *out++ = float(p.z);
            *out++ = colour[0], *out++ = colour[1], *out++ = colour[2];
        }
        auto& range = pieceRanges_[barPiece_[line.bar]]; // lines come piece by piece
        if (range.second == 0) range.first = GLint(2 * i);
        range.second += 2;
    }
    upload(barVbo_, barData_);
    barVertices_ = GLsizei(barData_.size() / 6);
}

void Renderer::draw(const Camera& camera, const Overlay& overlay) {
    glViewport(0, 0, camera.width(), camera.height());
    glClear(GL_DEPTH_BUFFER_BIT); // the background covers every pixel
    drawBackground();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    drawGrid(camera);
    drawRails(camera);
    drawBars(camera, overlay.highlight);
    drawGuides(camera, overlay.guides);
    drawSpheres(camera, overlay.spheres, false);
    drawSpheres(camera, overlay.translucent, true);
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(0);
}

void Renderer::drawBackground() {
    glDisable(GL_DEPTH_TEST);
    glUseProgram(backgroundProgram_);
    glUniform3fv(at(backgroundProgram_, "uTop"), 1, kBackgroundTop);
    glUniform3fv(at(backgroundProgram_, "uBottom"), 1, kBackgroundBottom);
    glBindVertexArray(emptyVao_);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

namespace {
void useLines(GLuint program, const Camera& camera, const Vec3& origin, float radius) {
    glUseProgram(program);
    setMatrix(program, "uViewProjection", camera.projection() * camera.view(origin));
    setMatrix(program, "uView", camera.view(origin));
    glUniform3fv(at(program, "uFogColour"), 1, kFog);
    glUniform2f(at(program, "uFogRange"), float(camera.distance - radius), float(camera.distance + radius));
    glUniform1f(at(program, "uAlpha"), 1.0f);
    glUniform1f(at(program, "uBrighten"), 0.0f);
    glUniform2i(at(program, "uBrightVertices"), 0, 0);
    glUniform1f(at(program, "uPointSize"), 1.0f);
}
} // namespace

void Renderer::drawGrid(const Camera& camera) {
    if (!gridVertices_) return;
    useLines(linesProgram_, camera, renderOrigin_, sceneRadius_);
    glUniform1f(at(linesProgram_, "uAlpha"), 0.35f);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    glBindVertexArray(gridVao_);
    glDrawArrays(GL_LINES, 0, gridVertices_);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
}

void Renderer::drawBars(const Camera& camera, PieceId highlight) {
    updateNetLines(camera);
    if (!barVertices_) return;
    useLines(linesProgram_, camera, renderOrigin_, sceneRadius_);
    // The highlighted piece, brighter, in the same pass: its lines are one range of vertices.
    const auto range = pieceRanges_.find(highlight);
    if (highlight && range != pieceRanges_.end()) {
        glUniform1f(at(linesProgram_, "uBrighten"), 0.45f);
        const auto [first, count] = range->second;
        glUniform2i(at(linesProgram_, "uBrightVertices"), first, first + count);
    }
    glBindVertexArray(barVao_);
    glDrawArrays(GL_LINES, 0, barVertices_);
    if (knotDots_) {
        glUniform2i(at(linesProgram_, "uBrightVertices"), 0, 0);
        glEnable(GL_PROGRAM_POINT_SIZE);
        glUniform1f(at(linesProgram_, "uPointSize"), camera.height() > 900 ? 3.0f : 2.5f);
        glBindVertexArray(knotVao_);
        glDrawArrays(GL_POINTS, 0, knotDots_);
        glDisable(GL_PROGRAM_POINT_SIZE);
    }
}

void Renderer::drawRails(const Camera& camera) {
    if (!railVertices_) return;
    glUseProgram(thickProgram_);
    setMatrix(thickProgram_, "uViewProjection", camera.projection() * camera.view(renderOrigin_));
    glUniform2f(at(thickProgram_, "uViewport"), float(camera.width()), float(camera.height()));
    glUniform1f(at(thickProgram_, "uWidth"), 7.0f);
    glUniform4fv(at(thickProgram_, "uColour"), 1, kRailColour);
    glBindVertexArray(railVao_);
    glDrawArrays(GL_LINES, 0, railVertices_);
}

void Renderer::drawGuides(const Camera& camera, const std::vector<std::pair<Vec3, Vec3>>& guides) {
    if (guides.empty()) return;
    std::vector<float> data;
    for (const auto& [a, b] : guides)
        for (const Vec3& p : {a, b}) {
            pushFromOrigin(data, p);
            data.insert(data.end(), {1.0f, 0.85f, 0.3f});
        }
    upload(guideVbo_, data);
    useLines(linesProgram_, camera, renderOrigin_, sceneRadius_);
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(guideVao_);
    glDrawArrays(GL_LINES, 0, GLsizei(data.size() / 6));
    glEnable(GL_DEPTH_TEST);
}

void Renderer::drawSpheres(const Camera& camera, const std::vector<Sphere>& spheres, bool blend) {
    if (spheres.empty()) return;
    std::vector<float> data;
    data.reserve(spheres.size() * 8);
    for (const Sphere& s : spheres) {
        pushFromOrigin(data, s.centre);
        data.insert(data.end(), {float(s.radius), s.rgba[0], s.rgba[1], s.rgba[2], s.rgba[3]});
    }
    glBindBuffer(GL_ARRAY_BUFFER, sphereInstanceVbo_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size() * sizeof(float)), data.data(), GL_STREAM_DRAW);
    glUseProgram(sphereProgram_);
    setMatrix(sphereProgram_, "uView", camera.view(renderOrigin_));
    setMatrix(sphereProgram_, "uProjection", camera.projection());
    if (blend) {
        glEnable(GL_BLEND);
        glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        glDepthMask(GL_FALSE);
    }
    glBindVertexArray(sphereVao_);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(spheres.size()));
    if (blend) {
        glDepthMask(GL_TRUE);
        glDisable(GL_BLEND);
    }
}

} // namespace netsculpt::studio
