#pragma once
// Draws the sculpture with OpenGL 3.3 core: bars as GL_LINES from a vertex buffer rebuilt when the
// relaxer publishes a shape (and, where runs of short bars are merged into one line on screen,
// NetLines.h, when the camera moves); knots of small nets as points, rails as thick shaded lines
// (a geometry shader widens them in screen space), handles as instanced sphere impostors, a
// ground grid and a gradient background.

#include "Gl.h"
#include "NetLines.h"

#include "interaction/Camera.h"
#include "model/Compiler.h"
#include "model/Sculpture.h"

#include <array>
#include <map>
#include <vector>

namespace netsculpt::studio {

enum class ColourBy { Piece, Tension };

/// Tension colour ramp: blue (low) - teal - yellow - red (the largest); slack bars grey.
std::array<float, 3> tensionColour(double tension, double maxTension);

/// One sphere to draw: centre (m), radius (m), colour (RGBA in [0, 1]).
struct Sphere {
    Vec3 centre;
    double radius = 0.05;
    std::array<float, 4> rgba{1, 1, 1, 1};
};

/// What the interaction layer adds on top of the net this frame.
struct Overlay {
    std::vector<Sphere> spheres;            ///< opaque handles
    std::vector<Sphere> translucent;        ///< hover highlight (drawn last, blended)
    std::vector<std::pair<Vec3, Vec3>> guides; ///< thin lines (the Connect drag)
    PieceId highlight;                      ///< piece drawn brighter (selected / under the mouse)
};

class Renderer {
  public:
    Renderer() = default;
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// Compiles the shaders and makes the buffers. Throws std::runtime_error with the GL log.
    void init();

    /// After a change of the model: rails, piece colours, the ground.
    void setSculpture(const Sculpture& s, const CompiledSculpture& compiled);
    /// After the knots moved (or the colouring changed): the bar colours; the lines follow at the
    /// next draw.
    void setPositions(const Sculpture& s, const MassSpringSystem& system, ColourBy colourBy);
    /// Largest bar tension of the last setPositions, N (for the legend).
    double maxTension() const { return maxTension_; }
    /// Lines drawn for the bars in the last frame (at most one per bar).
    std::size_t netLineCount() const { return lines_.size(); }
    /// Runs of bars within this many pixels of one straight line are drawn as that line
    /// (NetLines.h); 0 draws every bar (the default: a GPU has no need to merge).
    void setBarMergeTolerance(double pixels);

    void draw(const Camera& camera, const Overlay& overlay);

  private:
    void drawBackground();
    void drawGrid(const Camera& camera);
    void updateNetLines(const Camera& camera);
    void uploadNetLines();
    void uploadKnotDots();
    void drawBars(const Camera& camera, PieceId highlight);
    void drawRails(const Camera& camera);
    void drawSpheres(const Camera& camera, const std::vector<Sphere>& spheres, bool blend);
    void drawGuides(const Camera& camera, const std::vector<std::pair<Vec3, Vec3>>& guides);

    GLuint linesProgram_ = 0, thickProgram_ = 0, sphereProgram_ = 0, backgroundProgram_ = 0;
    GLuint barVao_ = 0, barVbo_ = 0;
    GLuint knotVao_ = 0, knotVbo_ = 0;
    GLuint railVao_ = 0, railVbo_ = 0;
    GLuint gridVao_ = 0, gridVbo_ = 0;
    GLuint guideVao_ = 0, guideVbo_ = 0;
    GLuint sphereVao_ = 0, sphereQuadVbo_ = 0, sphereInstanceVbo_ = 0;
    GLuint emptyVao_ = 0;
    GLsizei barVertices_ = 0, knotDots_ = 0, railVertices_ = 0, gridVertices_ = 0;

    // The net: topology from setSculpture, shape and colours from setPositions, lines per view.
    NetStrands strands_;
    std::vector<std::uint32_t> barA_, barB_;
    std::vector<PieceId> barPiece_;
    std::vector<Vec3> knotPositions_; ///< m, the sculpture's coordinates
    /// m; every vertex is handed to OpenGL as a float from here (the compiled system's origin),
    /// and the view matrices are taken from here too (Camera::view(origin)).
    Vec3 renderOrigin_;
    /// p - renderOrigin_ as floats, appended to `out`.
    void pushFromOrigin(std::vector<float>& out, const Vec3& p) const;
    std::vector<std::array<float, 3>> barColour_;
    std::vector<std::uint32_t> barColourKey_; ///< the colour quantized: lines never mix two keys
    std::vector<NetLine> lines_;
    double barMergeTolerance_ = 0;            ///< px
    bool linesStale_ = true;                  ///< the shape or colours changed since the lines were made
    std::array<float, 16> linesViewProjection_{}; ///< the camera the lines were made for
    int linesWidth_ = 0, linesHeight_ = 0;
    std::vector<float> barData_; ///< x y z r g b per vertex, two vertices per line
    std::map<PieceId, std::pair<GLint, GLsizei>> pieceRanges_; ///< first vertex, vertex count
    double maxTension_ = 0;
    float sceneRadius_ = 5;
};

} // namespace netsculpt::studio
