// glTF 2.0 binary (.glb) through tinygltf: bars as lines (or tubes) coloured by tension, rails as
// dark lines. This translation unit holds tinygltf's implementation; it is built without stb
// (no images are read or written), so stb's only copy is the static one in Raster.cpp.

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

std::string glbBytes(const ExportInput& in) {
    const double radius = in.options.tubeRadius;
    if (!(std::isfinite(radius) && radius >= 0))
        throw UserError("tube_radius must be a finite number >= 0 (m), got " +
                        formatNumber(radius));
    const std::string colourBy = in.options.colourBy == "piece" ? "piece" : "tension";
    const Scene scene = buildScene(in.sculpture, in.compiled, colourBy, in.status.relaxed);
    Builder g;
    g.model.materials.emplace_back();
    tinygltf::Material& material = g.model.materials.back();
    material.name = "rope";
    material.doubleSided = true;
    material.pbrMetallicRoughness.metallicFactor = 0;
    material.pbrMetallicRoughness.roughnessFactor = 1;
    material.extensions["KHR_materials_unlit"] = tinygltf::Value(tinygltf::Value::Object());
    g.model.extensionsUsed.push_back("KHR_materials_unlit");

    tinygltf::Mesh mesh;
    mesh.name = "netsculpt";
    std::vector<float> barPositions, barColours, barTension, railPositions, railColours;
    TubeMesh tubes;
    std::vector<float> tubeColours;
    // Vertices are floats: they are written from the system's origin, which the root node's
    // translation adds back (in site coordinates a float of the sculpture's own would be off by
    // up to half a metre).
    const Vec3 origin = in.compiled.system.origin;
    for (SceneSegment seg : scene.segments) {
        seg.a -= origin;
        seg.b -= origin;
        std::vector<float>& positions = seg.rail ? railPositions : barPositions;
        std::vector<float>& colours = seg.rail ? railColours : barColours;
        if (!seg.rail && radius > 0) {
            const std::size_t before = tubes.vertices.size();
            appendTube(tubes, seg.a, seg.b, radius);
            for (std::size_t i = before; i < tubes.vertices.size(); ++i)
                push(tubeColours, seg.colour);
            continue;
        }
        push(positions, seg.a);
        push(positions, seg.b);
        push(colours, seg.colour);
        push(colours, seg.colour);
        if (!seg.rail)
            barTension.insert(barTension.end(), 2, float(scene.tension[seg.bar]));
    }
    const auto lines = [&](const std::vector<float>& positions, const std::vector<float>& colours,
                           const std::vector<float>* tension) {
        if (positions.empty())
            return;
        tinygltf::Primitive p;
        p.mode = TINYGLTF_MODE_LINE;
        p.material = 0;
        p.attributes["POSITION"] = g.floats(positions, TINYGLTF_TYPE_VEC3, 3, true);
        p.attributes["COLOR_0"] = g.floats(colours, TINYGLTF_TYPE_VEC3, 3);
        if (tension)
            p.attributes["_TENSION"] = g.floats(*tension, TINYGLTF_TYPE_SCALAR, 1);
        mesh.primitives.push_back(p);
    };
    lines(barPositions, barColours, &barTension);
    if (!tubes.triangles.empty()) {
        std::vector<float> positions, normals;
        std::vector<std::uint32_t> indices;
        for (const Vec3& v : tubes.vertices)
            push(positions, v);
        for (const Vec3& n : tubes.normals)
            push(normals, n);
        for (const auto& t : tubes.triangles)
            indices.insert(indices.end(), t.begin(), t.end());
        tinygltf::Primitive p;
        p.mode = TINYGLTF_MODE_TRIANGLES;
        p.material = 0;
        p.attributes["POSITION"] = g.floats(positions, TINYGLTF_TYPE_VEC3, 3, true);
        p.attributes["NORMAL"] = g.floats(normals, TINYGLTF_TYPE_VEC3, 3);
        p.attributes["COLOR_0"] = g.floats(tubeColours, TINYGLTF_TYPE_VEC3, 3);
        p.indices = g.indices(indices);
        mesh.primitives.push_back(p);
    }
    lines(railPositions, railColours, nullptr);

    tinygltf::Node root;
    root.name = "netsculpt (z up)";
    root.rotation = {-std::sqrt(0.5), 0, 0, std::sqrt(0.5)}; // -90 deg about x: z up -> glTF's y up
    if (origin != Vec3{})
        root.translation = {origin.x, origin.z, -origin.y}; // the origin, turned the same way
    if (!mesh.primitives.empty()) {
        g.model.meshes.push_back(mesh);
        root.mesh = 0;
    }
    g.model.nodes.push_back(root);
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
