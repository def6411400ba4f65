// glTF 2.0 binary (.glb) through tinygltf: bars as lines (or tubes) coloured by tension, rails as
// dark lines; each piece a mesh and a node of its own under the root, which turns z up to glTF's
// y up. This translation unit holds tinygltf's implementation; it is built without stb (no
// images are read or written), so stb's only copy is the static one in Raster.cpp.

#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include "io/Exporters.h"
#include "io/Scene.h"
#include "model/Error.h"

#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

namespace netsculpt::io {

namespace {

/// Appends float data to the single buffer and adds a view and an accessor for it.
class Builder {
  public:
    tinygltf::Model model;

    Builder() {
        model.asset.version = "2.0";
        model.asset.generator = "netsculpt";
        model.buffers.emplace_back();
    }

    int floats(const std::vector<float>& data, int type, int components, bool minMax = false) {
        const int accessor =
            addView(data.data(), data.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
        tinygltf::Accessor& a = model.accessors[std::size_t(accessor)];
        a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
        a.type = type;
        a.count = data.size() / std::size_t(components);
        if (minMax) {
            a.minValues.assign(std::size_t(components), std::numeric_limits<double>::infinity());
            a.maxValues.assign(std::size_t(components), -std::numeric_limits<double>::infinity());
            for (std::size_t i = 0; i < data.size(); ++i) {
                const std::size_t c = i % std::size_t(components);
                a.minValues[c] = std::min(a.minValues[c], double(data[i]));
                a.maxValues[c] = std::max(a.maxValues[c], double(data[i]));
            }
        }
        return accessor;
    }

    int indices(const std::vector<std::uint32_t>& data) {
        const int accessor = addView(data.data(), data.size() * sizeof(std::uint32_t),
                                     TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        tinygltf::Accessor& a = model.accessors[std::size_t(accessor)];
        a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        a.type = TINYGLTF_TYPE_SCALAR;
        a.count = data.size();
        return accessor;
    }

  private:
    int addView(const void* data, std::size_t bytes, int target) {
        auto& buffer = model.buffers[0].data;
        while (buffer.size() % 4 != 0)
            buffer.push_back(0);
        tinygltf::BufferView view;
        view.buffer = 0;
        view.byteOffset = buffer.size();
        view.byteLength = bytes;
        view.target = target;
        const auto* begin = static_cast<const unsigned char*>(data);
        buffer.insert(buffer.end(), begin, begin + bytes);
        model.bufferViews.push_back(view);
        tinygltf::Accessor accessor;
        accessor.bufferView = int(model.bufferViews.size() - 1);
        model.accessors.push_back(accessor);
        return int(model.accessors.size() - 1);
    }
};

void push(std::vector<float>& out, const Vec3& v) {
    out.push_back(float(v.x));
    out.push_back(float(v.y));
    out.push_back(float(v.z));
}

void push(std::vector<float>& out, const Rgb& srgb) {
    const Colour c = toLinear(srgb);
    out.push_back(float(c.r));
    out.push_back(float(c.g));
    out.push_back(float(c.b));
}

} // namespace

namespace {

/// One piece's bars, or the rails: a mesh of its own and a node, so that a 3D or CAD program can
/// pick each piece apart.
struct Group {
    std::string name;
    std::vector<float> positions, colours, tension; ///< lines: two vertices a segment
    TubeMesh tubes;
    std::vector<float> tubeColours;
};

/// The scene's segments grouped by piece, in the order of their first bar, then the rails.
std::vector<Group> groupSegments(const ExportInput& in, const Scene& scene, double radius) {
    std::vector<Group> groups;
    std::map<std::uint32_t, std::size_t> groupOfPiece;
    Group rails{"rails", {}, {}, {}, {}, {}};
    const Vec3 origin = in.compiled.system.origin;
    for (SceneSegment seg : scene.segments) {
        // Floats from the system's origin, which the root node's translation adds back (in site
        // coordinates a float of the sculpture's own would be off by up to half a metre).
        seg.a -= origin;
        seg.b -= origin;
        Group* group = &rails;
        if (!seg.rail) {
            const PieceId piece = in.compiled.system.barPiece[seg.bar];
            const auto [at, added] = groupOfPiece.emplace(piece.value, groups.size());
            if (added)
                groups.push_back({toString(piece) + " (" + in.sculpture.pieces.at(piece).name +
                                      ")",
                                  {}, {}, {}, {}, {}});
            group = &groups[at->second];
        }
        if (!seg.rail && radius > 0) {
            const std::size_t before = group->tubes.vertices.size();
            appendTube(group->tubes, seg.a, seg.b, radius);
            for (std::size_t i = before; i < group->tubes.vertices.size(); ++i)
                push(group->tubeColours, seg.colour);
            continue;
        }
        push(group->positions, seg.a);
        push(group->positions, seg.b);
        push(group->colours, seg.colour);
        push(group->colours, seg.colour);
        if (!seg.rail)
            group->tension.insert(group->tension.end(), 2, float(scene.tension[seg.bar]));
    }
    groups.push_back(std::move(rails));
    return groups;
}

tinygltf::Primitive linesPrimitive(Builder& g, const Group& group) {
    tinygltf::Primitive p;
    p.mode = TINYGLTF_MODE_LINE;
    p.material = 0;
    p.attributes["POSITION"] = g.floats(group.positions, TINYGLTF_TYPE_VEC3, 3, true);
    p.attributes["COLOR_0"] = g.floats(group.colours, TINYGLTF_TYPE_VEC3, 3);
    if (!group.tension.empty())
        p.attributes["_TENSION"] = g.floats(group.tension, TINYGLTF_TYPE_SCALAR, 1);
    return p;
}

tinygltf::Primitive tubesPrimitive(Builder& g, const Group& group) {
    std::vector<float> positions, normals;
    std::vector<std::uint32_t> indices;
    for (const Vec3& v : group.tubes.vertices)
        push(positions, v);
    for (const Vec3& n : group.tubes.normals)
        push(normals, n);
    for (const auto& t : group.tubes.triangles)
        indices.insert(indices.end(), t.begin(), t.end());
    tinygltf::Primitive p;
    p.mode = TINYGLTF_MODE_TRIANGLES;
    p.material = 0;
    p.attributes["POSITION"] = g.floats(positions, TINYGLTF_TYPE_VEC3, 3, true);
    p.attributes["NORMAL"] = g.floats(normals, TINYGLTF_TYPE_VEC3, 3);
    p.attributes["COLOR_0"] = g.floats(group.tubeColours, TINYGLTF_TYPE_VEC3, 3);
    p.indices = g.indices(indices);
    return p;
}

void addMaterial(Builder& g) {
    g.model.materials.emplace_back();
    tinygltf::Material& material = g.model.materials.back();
    material.name = "rope";
    material.doubleSided = true;
    material.pbrMetallicRoughness.metallicFactor = 0;
    material.pbrMetallicRoughness.roughnessFactor = 1;
    material.extensions["KHR_materials_unlit"] = tinygltf::Value(tinygltf::Value::Object());
    g.model.extensionsUsed.push_back("KHR_materials_unlit");
}

} // namespace

std::string glbBytes(const ExportInput& in) {
    const double radius = in.options.tubeRadius;
    if (!(std::isfinite(radius) && radius >= 0))
        throw UserError("tube_radius must be a finite number >= 0 (m), got " +
                        formatNumber(radius));
    const std::string colourBy = in.options.colourBy == "piece" ? "piece" : "tension";
    const Scene scene = buildScene(in.sculpture, in.compiled, colourBy, in.status.relaxed);
    Builder g;
    addMaterial(g);

    const Vec3 origin = in.compiled.system.origin;
    tinygltf::Node root;
    root.name = "netsculpt (z up)";
    root.rotation = {-std::sqrt(0.5), 0, 0, std::sqrt(0.5)}; // -90 deg about x: z up -> glTF's y up
    if (origin != Vec3{})
        root.translation = {origin.x, origin.z, -origin.y}; // the origin, turned the same way
    g.model.nodes.push_back(root);
    for (const Group& group : groupSegments(in, scene, radius)) {
        tinygltf::Mesh mesh;
        mesh.name = group.name;
        if (!group.positions.empty())
            mesh.primitives.push_back(linesPrimitive(g, group));
        if (!group.tubes.triangles.empty())
            mesh.primitives.push_back(tubesPrimitive(g, group));
        if (mesh.primitives.empty())
            continue;
        g.model.meshes.push_back(mesh);
        tinygltf::Node node;
        node.name = group.name;
        node.mesh = int(g.model.meshes.size() - 1);
        g.model.nodes.push_back(node);
        g.model.nodes[0].children.push_back(int(g.model.nodes.size() - 1));
    }
    tinygltf::Scene sceneNode;
    sceneNode.name = scene.title;
    sceneNode.nodes = {0};
    g.model.scenes.push_back(sceneNode);
    g.model.defaultScene = 0;
    if (g.model.buffers[0].data.empty())
        g.model.buffers.clear();

    std::ostringstream out;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&g.model, out, false, true))
        throw UserError("glTF encoding failed");
    return std::move(out).str();
}

} // namespace netsculpt::io
