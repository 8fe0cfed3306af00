// glTF reading: tinygltf parses the JSON (or the GLB container) and reads the buffers; every
// accessor is then checked against its buffer view and buffer before a value is read, and the
// default scene's nodes are walked depth-first with their world transforms.
#include "scene/GltfLoader.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "image/InputError.h"
#include "image/AtomicFile.h"
#include "scene/GltfDraco.h"
#include "scene/GltfMeshopt.h"
#include "scene/SceneFile.h"

namespace gpurt {
namespace {

// More elements than this in one accessor is a damaged file, not a model (2^28 vertices).
constexpr uint64_t kMaxAccessorCount = uint64_t(1) << 28;

// The images tinygltf read (from a file, a data URI or a buffer view), decoded by gpurt's PNG and
// JPEG reader; one that cannot be decoded is kept as its error, so that the materials using it
// warn and keep their colour instead of failing the whole scene.
struct DecodedImages {
    std::string name;  // the glTF file
    std::map<int, Rgba8Image> images;
    std::map<int, std::string> errors;
};

bool decodeGltfImage(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
                     const unsigned char* bytes, int size, void* user) {
    // An image in a buffer view is decoded later (GltfReader::textureOf), with the view checked
    // against its buffer: tinygltf hands over the view's bytes without that check.
    if (image->bufferView >= 0) return true;
    DecodedImages& decoded = *static_cast<DecodedImages*>(user);
    const std::string what = "image " + std::to_string(index) + (image->uri.empty() || image->uri.compare(0, 5, "data:") == 0
                                                                      ? std::string()
                                                                      : " ('" + image->uri + "')");
    try {
        decoded.images[index] = decodeImage(bytes, size_t(std::max(size, 0)), what);
    } catch (const InputError& e) {
        decoded.errors[index] = e.what();
    }
    return true;
}

std::string firstLine(const std::string& text) {
    std::string line = text.substr(0, text.find('\n'));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    return line;
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The extensions gpurt reads (docs/SCENE_FORMAT.md); any other one a file uses is a warning.
const std::set<std::string> kExtensionsRead = {
    "KHR_draco_mesh_compression", "KHR_mesh_quantization", "KHR_materials_emissive_strength",
    "KHR_materials_transmission", "KHR_materials_ior",     "KHR_texture_transform",
    "KHR_lights_punctual",        "KHR_materials_unlit",       "EXT_meshopt_compression",
    "KHR_materials_clearcoat",    "KHR_materials_specular",    "KHR_materials_sheen",
    "KHR_materials_volume",       "KHR_materials_iridescence", "KHR_materials_anisotropy",
    "KHR_materials_pbrSpecularGlossiness", "EXT_mesh_gpu_instancing", "KHR_materials_dispersion"};

// A skinned node's joint matrices: each joint's world transform times its inverse bind matrix
// (the glTF spec, "Skins"); none for a node without a skin.
struct Skinning {
    int skin = -1;
    std::vector<glm::dmat4> joints;
};

// Where a primitive's vertices go: the node's world transform, or per vertex its skinning matrix
// (then the node's own transform is not used, as the glTF spec says of skinned meshes).
struct VertexMatrices {
    glm::dmat4 world{1.0};
    std::vector<glm::dmat4> skinned;  // one per vertex, or none
    const glm::dmat4& of(size_t v) const { return skinned.empty() ? world : skinned[v]; }
};

// A primitive with KHR_draco_mesh_compression: its decoded mesh and which attribute is which id.
struct DracoPrimitive {
    const tinygltf::Primitive* primitive = nullptr;
    DracoMesh mesh;
    std::map<std::string, int> ids;  // attribute name -> Draco unique id
};

class GltfReader {
  public:
    GltfReader(const tinygltf::Model& model, const std::string& name, DecodedImages& images)
        : m_(model), name_(name), images_(images) {}

    Scene read() {
        Scene scene;
        scene.materials.push_back(Material{});  // for primitives without a material
        materialIds_.assign(m_.materials.size(), -1);
        std::vector<int> roots;
        if (!m_.scenes.empty()) {
            const int s = m_.defaultScene >= 0 ? m_.defaultScene : 0;
            if (s >= int(m_.scenes.size())) fail("scene " + std::to_string(s) + " does not exist");
            roots = m_.scenes[size_t(s)].nodes;
        } else {  // no scene: every root node, in order
            std::vector<bool> child(m_.nodes.size(), false);
            for (const tinygltf::Node& n : m_.nodes)
                for (int c : n.children)
                    if (c >= 0 && c < int(m_.nodes.size())) child[size_t(c)] = true;
            for (size_t n = 0; n < m_.nodes.size(); ++n)
                if (!child[n]) roots.push_back(int(n));
        }
        warnUnusedExtensions();
        if (!m_.animations.empty())
            warn(std::to_string(m_.animations.size()) + " animation" +
                 (m_.animations.size() == 1 ? " is" : "s are") +
                 " not used; the scene is drawn at rest (its nodes' own transforms)");
        for (int n : roots) visit(n, glm::dmat4(1.0), scene);
        warnLeftOutPrimitives();
        if (scene.textures.empty()) scene.texcoords.clear();
        else scene.texcoords.resize(scene.triangles.size());
        return scene;
    }

  private:
    [[noreturn]] void fail(const std::string& what) const { failAt(FileLoc{name_}, what); }
    void warn(const std::string& what) const { warnAt(FileLoc{name_}, what); }

    glm::dmat4 localTransform(const tinygltf::Node& node, const std::string& at) const {
        if (!node.matrix.empty()) {
            if (node.matrix.size() != 16) fail(at + ": matrix of " + std::to_string(node.matrix.size()) + " numbers, not 16");
            return glm::make_mat4(node.matrix.data());  // column-major, as glTF
        }
        glm::dmat4 t(1.0);
        if (!node.translation.empty()) {
            if (node.translation.size() != 3) fail(at + ": translation is not 3 numbers");
            t = glm::translate(t, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
        }
        if (!node.rotation.empty()) {
            if (node.rotation.size() != 4) fail(at + ": rotation is not 4 numbers");
            const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);  // w, x, y, z
            t = t * glm::mat4_cast(glm::normalize(q));
        }
        if (!node.scale.empty()) {
            if (node.scale.size() != 3) fail(at + ": scale is not 3 numbers");
            t = glm::scale(t, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
        }
        return t;
    }

    // Where a node's mesh is drawn: at the node's world transform, or under EXT_mesh_gpu_instancing
    // once per instance at world x T x R x S of the instance's TRANSLATION, ROTATION (a unit
    // quaternion x, y, z, w) and SCALE (each optional, all of one count; float, or the normalized
    // integers the extension and KHR_mesh_quantization allow). Other attributes (custom ones such
    // as _ID) are a warning.
    std::vector<glm::dmat4> instances(const tinygltf::Node& node, const tinygltf::Mesh& mesh, const glm::dmat4& world,
                                      const std::string& at) {
        const auto ext = node.extensions.find("EXT_mesh_gpu_instancing");
        if (ext == node.extensions.end()) return {world};
        const std::string where = at + " EXT_mesh_gpu_instancing";
        if (!ext->second.IsObject() || !ext->second.Has("attributes") || !ext->second.Get("attributes").IsObject())
            fail(where + ": no attributes object");
        const tinygltf::Value& attributes = ext->second.Get("attributes");
        const char* names[3] = {"TRANSLATION", "ROTATION", "SCALE"};
        const int wanted[3] = {3, 4, 3};
        int accessors[3] = {-1, -1, -1};
        size_t count = 0;
        bool any = false;
        for (const std::string& key : attributes.Keys()) {
            const auto known = std::find_if(std::begin(names), std::end(names), [&](const char* n) { return key == n; });
            if (known == std::end(names)) {
                warnOnce("instancing " + key, where + ": attribute " + key + " is not used");
                continue;
            }
            const size_t k = size_t(known - std::begin(names));
            if (!wholeNumber(attributes.Get(key), accessors[k])) fail(where + ": " + key + " is not an accessor index");
            if (accessors[k] < 0 || accessors[k] >= int(m_.accessors.size()))
                fail(where + " " + key + ": accessor " + std::to_string(accessors[k]) + " does not exist");
            const size_t n = m_.accessors[size_t(accessors[k])].count;
            if (any && n != count)
                fail(where + ": " + key + " has " + std::to_string(n) + " instances, another attribute " + std::to_string(count));
            count = n;
            any = true;
        }
        if (!any) fail(where + ": none of TRANSLATION, ROTATION, SCALE");
        // The copies' vertices (or indices) within what one accessor may hold, so that a small file
        // (a sparse accessor needs no data) cannot ask for more than memory holds.
        const uint64_t elements = meshElements(mesh);
        if (count > 0 && elements > kMaxAccessorCount / count)
            fail(where + ": " + std::to_string(count) + " instances of " + std::to_string(elements) + " vertices are too many");
        std::vector<double> trs[3];
        for (size_t k = 0; k < 3; ++k) {
            if (accessors[k] < 0) continue;
            int components = 0;
            trs[k] = values(accessors[k], where + " " + names[k], components);
            if (components != wanted[k])
                fail(where + ": " + names[k] + " has " + std::to_string(components) + " components, not " + std::to_string(wanted[k]));
        }
        std::vector<glm::dmat4> placed;
        placed.reserve(count);
        for (size_t i = 0; i < count; ++i) {
            placed.push_back(world * instanceTransform(trs, i, where));
            for (int k = 0; k < 16; ++k)
                if (!std::isfinite(glm::value_ptr(placed.back())[k]))
                    fail(where + ": instance " + std::to_string(i) + "'s transform is not finite");
        }
        return placed;
    }

    // The vertices (or indices, where indexed) of a mesh's primitives.
    uint64_t meshElements(const tinygltf::Mesh& mesh) const {
        uint64_t elements = 0;
        for (const tinygltf::Primitive& p : mesh.primitives) {
            const auto position = p.attributes.find("POSITION");
            const int a = p.indices >= 0 ? p.indices : position != p.attributes.end() ? position->second : -1;
            if (a >= 0 && a < int(m_.accessors.size())) elements += m_.accessors[size_t(a)].count;
        }
        return elements;
    }

    // Instance i's T x R x S of its TRANSLATION, ROTATION (x, y, z, w) and SCALE values (each
    // empty when not given).
    glm::dmat4 instanceTransform(const std::vector<double> (&trs)[3], size_t i, const std::string& where) const {
        glm::dmat4 t(1.0);
        if (!trs[0].empty()) t = glm::translate(t, glm::dvec3(trs[0][3 * i], trs[0][3 * i + 1], trs[0][3 * i + 2]));
        if (!trs[1].empty()) {
            const glm::dquat q(trs[1][4 * i + 3], trs[1][4 * i], trs[1][4 * i + 1], trs[1][4 * i + 2]);  // w, x, y, z
            if (!(glm::length(q) > 0.0)) fail(where + ": instance " + std::to_string(i) + "'s rotation is zero");
            t = t * glm::mat4_cast(glm::normalize(q));
        }
        if (!trs[2].empty()) t = glm::scale(t, glm::dvec3(trs[2][3 * i], trs[2][3 * i + 1], trs[2][3 * i + 2]));
        return t;
    }

    void visit(int index, const glm::dmat4& parent, Scene& scene) {
        if (index < 0 || index >= int(m_.nodes.size())) fail("node " + std::to_string(index) + " does not exist");
        if (!onPath_.insert(index).second) fail("node " + std::to_string(index) + " is its own ancestor");
        const tinygltf::Node& node = m_.nodes[size_t(index)];
        const std::string at = "node " + std::to_string(index);
        const glm::dmat4 world = parent * localTransform(node, at);
        for (int k = 0; k < 16; ++k)
            if (!std::isfinite(glm::value_ptr(world)[k])) fail(at + ": its transform is not finite");
        if (node.mesh >= 0) {
            if (node.mesh >= int(m_.meshes.size())) fail(at + ": mesh " + std::to_string(node.mesh) + " does not exist");
            const tinygltf::Mesh& mesh = m_.meshes[size_t(node.mesh)];
            const Skinning skinning = skinningOf(node, at);
            const std::vector<double> weights = morphWeights(node, mesh, at);
            for (const glm::dmat4& placed : instances(node, mesh, world, at))
                for (size_t p = 0; p < mesh.primitives.size(); ++p)
                    primitive(mesh.primitives[p],
                              "mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(p),
                              placed, skinning, weights, scene);
        }
        if (node.camera >= 0) camera(node.camera, world, at, scene);
        const auto light = node.extensions.find("KHR_lights_punctual");
        if (light != node.extensions.end() && light->second.Has("light")) punctualLight(light->second.Get("light"), world, at, scene);
        for (int child : node.children) visit(child, world, scene);
        onPath_.erase(index);
    }

    // glTF's normalisation of an integer component (the glTF 2.0 spec's formulas: c / 127 clamped
    // to -1 for bytes, c / 255 for unsigned bytes, and so on); other types as they are.
    static double normalizedComponent(double c, int type) {
        switch (type) {
            case TINYGLTF_COMPONENT_TYPE_BYTE:
                return std::max(c / 127.0, -1.0);
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                return c / 255.0;
            case TINYGLTF_COMPONENT_TYPE_SHORT:
                return std::max(c / 32767.0, -1.0);
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
                return c / 65535.0;
        }
        return c;
    }

    // One component of an element, as a double (normalized integers mapped to [0, 1] or [-1, 1]).
    static double component(const unsigned char* p, int type, bool normalized) {
        double v = 0.0;
        switch (type) {
            case TINYGLTF_COMPONENT_TYPE_BYTE: {
                int8_t c;
                std::memcpy(&c, p, 1);
                v = c;
                break;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                v = p[0];
                break;
            case TINYGLTF_COMPONENT_TYPE_SHORT: {
                int16_t c;
                std::memcpy(&c, p, 2);
                v = c;
                break;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                uint16_t c;
                std::memcpy(&c, p, 2);
                v = c;
                break;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
                uint32_t c;
                std::memcpy(&c, p, 4);
                return c;
            }
            case TINYGLTF_COMPONENT_TYPE_FLOAT: {
                float c;
                std::memcpy(&c, p, 4);
                return c;
            }
            default:
                return 0.0;
        }
        return normalized ? normalizedComponent(v, type) : v;
    }

    // `count` elements of `components` values from a buffer view, each checked to lie inside the
    // view and the buffer.
    void readView(int viewIndex, size_t byteOffset, size_t count, int components, int type, bool normalized,
                  const std::string& at, std::vector<double>& out, size_t stride = 0) const {
        if (viewIndex < 0 || viewIndex >= int(m_.bufferViews.size()))
            fail(at + ": buffer view " + std::to_string(viewIndex) + " does not exist");
        const tinygltf::BufferView& view = m_.bufferViews[size_t(viewIndex)];
        if (view.buffer < 0 || view.buffer >= int(m_.buffers.size()))
            fail(at + ": buffer " + std::to_string(view.buffer) + " does not exist");
        const std::vector<unsigned char>& data = m_.buffers[size_t(view.buffer)].data;
        if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
            fail(at + ": buffer view " + std::to_string(viewIndex) + " (" + std::to_string(view.byteLength) +
                 " bytes at " + std::to_string(view.byteOffset) + ") runs past its buffer of " +
                 std::to_string(data.size()) + " bytes");
        const size_t size = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(type)));
        const size_t element = size * size_t(components);
        if (stride == 0) stride = view.byteStride ? view.byteStride : element;
        if (stride < element || stride % size != 0)
            fail(at + ": byte stride " + std::to_string(stride) + " does not fit elements of " + std::to_string(element) + " bytes");
        if (count == 0) return;
        // byteOffset + (count - 1) stride + element <= byteLength, without overflow.
        const size_t room = byteOffset <= view.byteLength ? view.byteLength - byteOffset : 0;
        if (byteOffset > view.byteLength || element > room || (count - 1) > (room - element) / stride)
            fail(at + ": " + std::to_string(count) + " elements do not fit buffer view " + std::to_string(viewIndex) + " (" +
                 std::to_string(view.byteLength) + " bytes)");
        const unsigned char* base = data.data() + view.byteOffset + byteOffset;
        out.resize(count * size_t(components));
        for (size_t k = 0; k < count; ++k)
            for (int c = 0; c < components; ++c)
                out[k * size_t(components) + size_t(c)] = component(base + k * stride + size_t(c) * size, type, normalized);
    }

    // An accessor's values (count x components), sparse substitutions applied.
    std::vector<double> values(int index, const std::string& at, int& components) const {
        if (index < 0 || index >= int(m_.accessors.size())) fail(at + ": accessor " + std::to_string(index) + " does not exist");
        const tinygltf::Accessor& a = m_.accessors[size_t(index)];
        const std::string where = at + " (accessor " + std::to_string(index) + ")";
        components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
        if (components <= 0 || tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType)) <= 0)
            fail(where + ": unknown type or component type");
        if (a.count > kMaxAccessorCount) fail(where + ": " + std::to_string(a.count) + " elements");
        std::vector<double> out;
        if (a.bufferView >= 0) {
            readView(a.bufferView, a.byteOffset, a.count, components, a.componentType, a.normalized, where, out);
        } else {
            if (!a.sparse.isSparse) fail(where + ": no buffer view and not sparse");
            out.assign(a.count * size_t(components), 0.0);
        }
        if (a.sparse.isSparse) {
            const size_t n = size_t(std::max(a.sparse.count, 0));
            if (n > a.count) fail(where + ": " + std::to_string(n) + " sparse values for " + std::to_string(a.count) + " elements");
            std::vector<double> indices, substitutes;
            const int indexType = a.sparse.indices.componentType;
            if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
                fail(where + ": sparse indices of component type " + std::to_string(indexType));
            readView(a.sparse.indices.bufferView, size_t(std::max(a.sparse.indices.byteOffset, 0)), n, 1, indexType, false,
                     where + " sparse indices", indices, size_t(tinygltf::GetComponentSizeInBytes(uint32_t(indexType))));
            readView(a.sparse.values.bufferView, size_t(std::max(a.sparse.values.byteOffset, 0)), n, components,
                     a.componentType, a.normalized, where + " sparse values", substitutes,
                     size_t(components) * size_t(tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType))));
            for (size_t k = 0; k < n; ++k) {
                if (indices[k] >= double(a.count) || (k > 0 && !(indices[k] > indices[k - 1])))
                    fail(where + ": sparse index " + std::to_string(uint64_t(indices[k])) + " out of range or order");
                for (int c = 0; c < components; ++c)
                    out[size_t(indices[k]) * size_t(components) + size_t(c)] = substitutes[k * size_t(components) + size_t(c)];
            }
        }
        return out;
    }

    // A JSON number that is a whole number in int's range (tinygltf's GetNumberAsInt would cast any
    // double); false for anything else.
    static bool wholeNumber(const tinygltf::Value& v, int& out) {
        if (!v.IsNumber()) return false;
        const double d = v.GetNumberAsDouble();
        if (!(d >= double(INT_MIN) && d <= double(INT_MAX)) || d != std::floor(d)) return false;
        out = int(d);
        return true;
    }

    // The decoded Draco mesh of a primitive with KHR_draco_mesh_compression (decoded once, kept
    // while the next primitives are the same one); null without the extension.
    const DracoPrimitive* dracoOf(const tinygltf::Primitive& prim, const std::string& at) const {
        const auto extension = prim.extensions.find("KHR_draco_mesh_compression");
        if (extension == prim.extensions.end()) return nullptr;
        if (draco_.primitive == &prim) return &draco_;
        const tinygltf::Value& e = extension->second;
        const std::string where = at + " KHR_draco_mesh_compression";
        int viewIndex = -1;
        if (!e.IsObject() || !wholeNumber(e.Get("bufferView"), viewIndex))
            fail(where + ": no bufferView");
        if (viewIndex < 0 || viewIndex >= int(m_.bufferViews.size()))
            fail(where + ": buffer view " + std::to_string(viewIndex) + " does not exist");
        const tinygltf::BufferView& view = m_.bufferViews[size_t(viewIndex)];
        if (view.buffer < 0 || view.buffer >= int(m_.buffers.size()))
            fail(where + ": buffer " + std::to_string(view.buffer) + " does not exist");
        const std::vector<unsigned char>& data = m_.buffers[size_t(view.buffer)].data;
        if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
            fail(where + ": buffer view " + std::to_string(viewIndex) + " (" +
                 std::to_string(view.byteLength) + " bytes at " + std::to_string(view.byteOffset) +
                 ") runs past its buffer of " + std::to_string(data.size()) + " bytes");
        DracoPrimitive decoded;
        const tinygltf::Value& attributes = e.Get("attributes");
        if (!attributes.IsObject()) fail(where + ": no attributes");
        for (const std::string& name : attributes.Keys()) {
            int id = -1;
            if (!wholeNumber(attributes.Get(name), id) || id < 0)
                fail(where + ": attribute " + name + " is no attribute id");
            decoded.ids[name] = id;
        }
        decoded.mesh = decodeDracoMesh(data.data() + view.byteOffset, view.byteLength,
                                       kMaxAccessorCount, FileLoc{name_}, at);
        decoded.primitive = &prim;
        draco_ = std::move(decoded);
        return &draco_;
    }

    // The values of attribute `name` of a primitive (count x components): from its Draco data
    // when KHR_draco_mesh_compression names it, else from its accessor (with every component type
    // and `normalized` flag glTF and KHR_mesh_quantization allow).
    std::vector<double> attributeValues(const tinygltf::Primitive& prim, const std::string& name,
                                        const std::string& at, int& components) const {
        const auto attribute = prim.attributes.find(name);
        if (attribute == prim.attributes.end()) fail(at + ": no " + name);
        const DracoPrimitive* draco = dracoOf(prim, at);
        const auto id =
            draco ? draco->ids.find(name) : std::map<std::string, int>::const_iterator();
        if (!draco || id == draco->ids.end())
            return values(attribute->second, at + " " + name, components);
        const auto decoded = draco->mesh.attributes.find(id->second);
        if (decoded == draco->mesh.attributes.end())
            fail(at + ": Draco data has no attribute " + std::to_string(id->second) + " (" + name +
                 ")");
        if (attribute->second < 0 || attribute->second >= int(m_.accessors.size()))
            fail(at + " " + name + ": accessor " + std::to_string(attribute->second) +
                 " does not exist");
        const tinygltf::Accessor& a = m_.accessors[size_t(attribute->second)];
        components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
        if (components != decoded->second.components)
            fail(at + ": Draco attribute " + std::to_string(id->second) + " (" + name + ") has " +
                 std::to_string(decoded->second.components) + " components, its accessor " +
                 std::to_string(components));
        std::vector<double> out = decoded->second.values;
        if (a.normalized && decoded->second.integer)
            for (double& c : out) c = normalizedComponent(c, a.componentType);
        return out;
    }

    void warnOnce(const std::string& key, const std::string& what) {
        if (warned_.insert(key).second) warn(what);
    }

    // What leaving out an extension gpurt knows of but does not read changes in the picture.
    static std::string whatIsLeftOut(const std::string& extension) {
        static const std::map<std::string, std::string> kLeftOut = {
            {"KHR_materials_variants", "each primitive's default material is drawn, not its variants"},
            {"KHR_materials_diffuse_transmission", "no light passes through surfaces diffusely"},
            {"KHR_animation_pointer", "the scene is drawn at rest"}};
        const auto found = kLeftOut.find(extension);
        return found == kLeftOut.end() ? std::string() : ": " + found->second;
    }

    // Every extension the file uses or requires that gpurt does not read: one warning each.
    void warnUnusedExtensions() {
        std::vector<std::string> named = m_.extensionsUsed;
        named.insert(named.end(), m_.extensionsRequired.begin(), m_.extensionsRequired.end());
        for (const std::string& extension : named) {
            if (kExtensionsRead.count(extension)) continue;
            const bool required =
                std::find(m_.extensionsRequired.begin(), m_.extensionsRequired.end(), extension) !=
                m_.extensionsRequired.end();
            const std::string leftOut = whatIsLeftOut(extension);
            const std::string requiredNote = !required       ? std::string()
                                             : leftOut.empty() ? " (the file requires it: the picture may be wrong)"
                                                               : " (the file requires it)";
            warnOnce("extension " + extension, "extension " + extension + " is not used" + requiredNote + leftOut);
        }
    }

    // Primitive attributes gpurt does not use, each named once: JOINTS_n and WEIGHTS_n of a node
    // without a skin, names glTF does not define, and morph targets' attributes other than POSITION,
    // NORMAL and TANGENT. (TANGENT, COLOR_n and TEXCOORD_n belong to the materials.)
    void warnUnusedAttributes(const tinygltf::Primitive& prim, const std::string& at,
                              const Skinning& skinning) {
        for (const auto& attribute : prim.attributes) {
            const std::string& name = attribute.first;
            auto is = [&](const char* prefix) { return name.rfind(prefix, 0) == 0; };
            if (name == "POSITION" || name == "NORMAL" || name == "TANGENT" || is("TEXCOORD_") ||
                is("COLOR_"))
                continue;
            if (is("JOINTS_") || is("WEIGHTS_")) {
                if (skinning.skin < 0)
                    warnOnce(
                        "attribute " + name,
                        at + ": " + name + " is not used (no node with a skin draws this mesh)");
                continue;
            }
            warnOnce("attribute " + name, at + ": attribute " + name + " is not used");
        }
        // Morph targets displace POSITION, NORMAL and TANGENT (morph); others (TEXCOORD_n, COLOR_n) not.
        for (const auto& target : prim.targets)
            for (const auto& attribute : target)
                if (attribute.first != "POSITION" && attribute.first != "NORMAL" && attribute.first != "TANGENT")
                    warnOnce("target attribute " + attribute.first,
                             at + ": morph target attribute " + attribute.first + " is not used");
    }

    // Points and lines (left out): one warning per mode, naming the first primitive.
    void warnLeftOutPrimitives() {
        static const char* const kModes[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
        for (const auto& [mode, leftOut] : leftOut_)
            warn(leftOut.first + ": mode " + kModes[mode] +
                 " is not triangles and is left out (gpurt draws triangles)" +
                 (leftOut.count == 2  ? std::string("; so is 1 more primitive of that mode")
                  : leftOut.count > 2 ? "; so are " + std::to_string(leftOut.count - 1) +
                                            " more primitives of that mode"
                                      : std::string()));
    }

    // The world transform of any node (a joint need not be in the default scene): its ancestors'
    // transforms and its own.
    glm::dmat4 worldOf(int index, const std::string& at) {
        if (parents_.empty()) {
            parents_.assign(m_.nodes.size(), -1);
            for (size_t n = 0; n < m_.nodes.size(); ++n)
                for (int c : m_.nodes[n].children)
                    if (c >= 0 && c < int(m_.nodes.size()) && parents_[size_t(c)] < 0 &&
                        c != int(n))
                        parents_[size_t(c)] = int(n);
        }
        glm::dmat4 world(1.0);
        size_t steps = 0;
        for (int n = index; n >= 0; n = parents_[size_t(n)]) {
            if (++steps > m_.nodes.size())
                fail(at + ": node " + std::to_string(index) + " is its own ancestor");
            world = localTransform(m_.nodes[size_t(n)], "node " + std::to_string(n)) * world;
        }
        return world;
    }

    // The joint matrices of a node's skin (computed once per skin). Joints that are no node,
    // an inverseBindMatrices accessor that does not exist or whose count is not the joints',
    // and matrices that are not finite are errors naming the skin.
    Skinning skinningOf(const tinygltf::Node& node, const std::string& at) {
        Skinning skinning;
        if (node.skin < 0 || node.mesh < 0) return skinning;
        if (node.skin >= int(m_.skins.size()))
            fail(at + ": skin " + std::to_string(node.skin) + " does not exist");
        skinning.skin = node.skin;
        if (auto seen = skins_.find(node.skin); seen != skins_.end()) {
            skinning.joints = seen->second;
            return skinning;
        }
        const tinygltf::Skin& skin = m_.skins[size_t(node.skin)];
        const std::string where = "skin " + std::to_string(node.skin);
        if (skin.joints.empty()) fail(where + ": no joints");
        std::vector<double> inverseBind;
        if (skin.inverseBindMatrices >= 0) {
            int components = 0;
            inverseBind =
                values(skin.inverseBindMatrices, where + " inverseBindMatrices", components);
            if (components != 16) fail(where + ": inverseBindMatrices is not MAT4");
            if (inverseBind.size() != 16 * skin.joints.size())
                fail(where + ": " + std::to_string(inverseBind.size() / 16) +
                     " inverseBindMatrices for " + std::to_string(skin.joints.size()) + " joints");
        }
        for (size_t j = 0; j < skin.joints.size(); ++j) {
            const int joint = skin.joints[j];
            if (joint < 0 || joint >= int(m_.nodes.size()))
                fail(where + ": joint " + std::to_string(j) + " is node " + std::to_string(joint) +
                     ", which does not exist");
            glm::dmat4 matrix = worldOf(joint, where + " joint " + std::to_string(j));
            if (!inverseBind.empty())
                matrix = matrix * glm::make_mat4(inverseBind.data() + 16 * j);  // column-major
            for (int k = 0; k < 16; ++k)
                if (!std::isfinite(glm::value_ptr(matrix)[k]))
                    fail(where + ": joint " + std::to_string(j) + "'s matrix is not finite");
            skinning.joints.push_back(matrix);
        }
        skins_[node.skin] = skinning.joints;
        return skinning;
    }

    // Joint set `set` (JOINTS_set, WEIGHTS_set, VEC4 each, one per vertex) added into each
    // vertex's blend of joint matrices and its sum of weights.
    void blendJointSet(const tinygltf::Primitive& prim, int set, const std::string& at, const Skinning& skinning,
                       std::vector<glm::dmat4>& blend, std::vector<double>& sums) {
        const size_t vertices = blend.size();
        const std::string jointsName = "JOINTS_" + std::to_string(set),
                          weightsName = "WEIGHTS_" + std::to_string(set);
        int jointComponents = 0, weightComponents = 0;
        const std::vector<double> joints =
            attributeValues(prim, jointsName, at, jointComponents);
        const std::vector<double> weights =
            attributeValues(prim, weightsName, at, weightComponents);
        if (jointComponents != 4 || joints.size() != 4 * vertices)
            fail(at + ": " + jointsName + " is not VEC4 of one per vertex");
        if (weightComponents != 4 || weights.size() != 4 * vertices)
            fail(at + ": " + weightsName + " is not VEC4 of one per vertex");
        for (size_t v = 0; v < vertices; ++v)
            for (size_t k = 0; k < 4; ++k) {
                const double joint = joints[4 * v + k], weight = weights[4 * v + k];
                if (!(joint >= 0.0 && joint < double(skinning.joints.size())) ||
                    joint != std::floor(joint))
                    fail(at + ": " + jointsName + " of vertex " + std::to_string(v) +
                         " names joint " +
                         (std::isfinite(joint)
                              ? std::to_string(int64_t(std::clamp(joint, -1e18, 1e18)))
                              : std::string("?")) +
                         "; skin " + std::to_string(skinning.skin) + " has " +
                         std::to_string(skinning.joints.size()) + " joints");
                if (!(weight >= 0.0) || !std::isfinite(weight))
                    fail(at + ": " + weightsName + " of vertex " + std::to_string(v) +
                         " is negative or not a number");
                if (weight == 0.0) continue;
                blend[v] += weight * skinning.joints[size_t(joint)];
                sums[v] += weight;
            }
    }

    // Sets past the first incomplete one (JOINTS_n without WEIGHTS_n, or a gap) are not used: a
    // warning each.
    void warnUnusedJointSets(const tinygltf::Primitive& prim, int set, const std::string& at) {
        for (const auto& attribute : prim.attributes) {
            const std::string& name = attribute.first;
            if (name.rfind("JOINTS_", 0) != 0 && name.rfind("WEIGHTS_", 0) != 0) continue;
            bool used = false;
            for (int k = 0; k < set; ++k)
                used = used || name == "JOINTS_" + std::to_string(k) ||
                       name == "WEIGHTS_" + std::to_string(k);
            if (!used)
                warnOnce("attribute " + name,
                         at + ": " + name +
                             " is not used (the complete sets of JOINTS_n and WEIGHTS_n are " +
                             std::to_string(set) + ")");
        }
    }

    // Per vertex, the matrix that takes POSITION to the scene: the node's world transform, or on a
    // skinned node the blend of its joints' matrices by JOINTS_n / WEIGHTS_n (every set given).
    // Weights that do not sum to 1 are normalised (a warning when they are off by more than 1%);
    // a vertex with no weight at all keeps the node's transform (a warning).
    VertexMatrices vertexMatrices(const tinygltf::Primitive& prim, const std::string& at,
                                  const glm::dmat4& world, const Skinning& skinning,
                                  size_t vertices) {
        VertexMatrices matrices;
        matrices.world = world;
        if (skinning.skin < 0) return matrices;
        if (!prim.attributes.count("JOINTS_0") || !prim.attributes.count("WEIGHTS_0")) {
            warnOnce("unskinned " + at,
                     at + ": its node has skin " + std::to_string(skinning.skin) +
                         " but it has no JOINTS_0 and WEIGHTS_0; drawn with its node's transform");
            return matrices;
        }
        std::vector<glm::dmat4> blend(vertices, glm::dmat4(0.0));
        std::vector<double> sums(vertices, 0.0);
        int set = 0;
        while (prim.attributes.count("JOINTS_" + std::to_string(set)) &&
               prim.attributes.count("WEIGHTS_" + std::to_string(set)))
            blendJointSet(prim, set++, at, skinning, blend, sums);
        warnUnusedJointSets(prim, set, at);
        size_t unweighted = 0, renormalised = 0;
        for (size_t v = 0; v < vertices; ++v) {
            if (!(sums[v] > 0.0)) {
                blend[v] = world;
                ++unweighted;
                continue;
            }
            if (std::abs(sums[v] - 1.0) > 0.01) ++renormalised;
            if (sums[v] != 1.0) blend[v] /= sums[v];
        }
        if (unweighted)
            warn(at + ": " + std::to_string(unweighted) +
                 " vertices have no joint weight; they keep their node's transform");
        if (renormalised)
            warn(at + ": the joint weights of " + std::to_string(renormalised) +
                 " vertices do not sum to 1; normalised");
        matrices.skinned = std::move(blend);
        return matrices;
    }

    // One primitive's triangles in world space (from TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN; a
    // Draco-compressed one from its decoded faces), with its vertex normals, and texture
    // coordinates when its material has a texture. A skinned node's primitive is posed by its
    // joints (vertexMatrices). Points and lines are left out, with a warning at the end.
    // The weights of a mesh's morph targets at rest (the glTF spec, "Morph Targets"): the node's
    // `weights`, else the mesh's, else none (every target at 0); each finite.
    std::vector<double> morphWeights(const tinygltf::Node& node, const tinygltf::Mesh& mesh, const std::string& at) const {
        const std::vector<double>& weights = !node.weights.empty() ? node.weights : mesh.weights;
        for (double w : weights)
            if (!std::isfinite(w)) fail(at + ": a morph target weight is not finite");
        return weights;
    }

    // Adds a primitive's morph targets' displacements of attribute `name` (VEC3, one per vertex),
    // each times its weight, to `data` (`stride` numbers per vertex, the first three displaced; the
    // spec's morphing, before skinning). A target without `name` displaces nothing; a weight count
    // other than the targets' is refused. Draco-compressed vertices may be reordered against the
    // targets' accessors: a warning, not morphed.
    void morph(const tinygltf::Primitive& prim, const std::string& at, const std::vector<double>& weights,
               const std::string& name, size_t stride, std::vector<double>& data) {
        if (prim.targets.empty() || std::all_of(weights.begin(), weights.end(), [](double w) { return w == 0.0; })) return;
        if (weights.size() != prim.targets.size())
            fail(at + ": " + std::to_string(weights.size()) + " morph target weights for " +
                 std::to_string(prim.targets.size()) + " targets");
        if (dracoOf(prim, at)) {
            warnOnce("draco targets " + at, at + ": morph targets of a Draco-compressed primitive are not applied");
            return;
        }
        const size_t vertices = data.size() / stride;
        for (size_t t = 0; t < prim.targets.size(); ++t) {
            const auto found = prim.targets[t].find(name);
            if (found == prim.targets[t].end() || weights[t] == 0.0) continue;
            const std::string where = at + " target " + std::to_string(t) + " " + name;
            // Its count checked before it is read (a sparse accessor of any count needs no data).
            if (found->second >= 0 && found->second < int(m_.accessors.size()) &&
                m_.accessors[size_t(found->second)].count != vertices)
                fail(where + ": not VEC3 of one per vertex");
            int components = 0;
            const std::vector<double> d = values(found->second, where, components);
            if (components != 3 || d.size() != 3 * vertices) fail(where + ": not VEC3 of one per vertex");
            for (size_t v = 0; v < vertices; ++v)
                for (size_t c = 0; c < 3; ++c) data[stride * v + c] += weights[t] * d[3 * v + c];
        }
    }

    void primitive(const tinygltf::Primitive& prim, const std::string& at, const glm::dmat4& world,
                   const Skinning& skinning, const std::vector<double>& weights, Scene& scene) {
        int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
        if (mode > TINYGLTF_MODE_TRIANGLE_FAN)
            fail(at + ": mode " + std::to_string(mode) + " is no glTF primitive mode");
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            LeftOut& leftOut = leftOut_[mode];
            if (leftOut.count++ == 0) leftOut.first = at;
            return;
        }
        warnUnusedAttributes(prim, at, skinning);
        if (dracoOf(prim, at)) {
            // The extension allows TRIANGLES and TRIANGLE_STRIP; Draco's faces are triangles either
            // way.
            if (mode == TINYGLTF_MODE_TRIANGLE_FAN)
                fail(at +
                     ": KHR_draco_mesh_compression with mode TRIANGLE_FAN (it allows TRIANGLES and "
                     "TRIANGLE_STRIP)");
            mode = TINYGLTF_MODE_TRIANGLES;
        }
        std::vector<double> position = positionValues(prim, at);
        morph(prim, at, weights, "POSITION", 3, position);
        const size_t vertices = position.size() / 3;
        const VertexMatrices matrices = vertexMatrices(prim, at, world, skinning, vertices);
        const std::vector<glm::vec3> positions = primitivePositions(position, at, matrices);
        const std::vector<glm::vec3> normals = primitiveNormals(prim, at, matrices, vertices, weights);
        const uint32_t material = materialOf(prim.material, scene);
        const std::vector<glm::vec2> texcoords = primitiveTexcoords(prim, at, material, vertices);
        const std::vector<glm::vec3> colors = primitiveColors(prim, at, vertices);
        const std::vector<glm::vec4> tangents = primitiveTangents(prim, at, matrices, vertices, material, normals, weights, scene);
        const std::vector<uint32_t> index = primitiveIndices(prim, at, vertices);
        if (scene.materials[material].hasAnisotropy() && tangents.empty() && texcoords.empty()) warnNoTangentFrame(at);
        // The glTF spec: a node whose world transform has a negative determinant (a mirror)
        // turns its primitives' front faces clockwise; the scene's triangles are counter-clockwise
        // at the front (Material::doubleSided), so such a primitive's corners 1 and 2 swap. (A
        // skinned primitive keeps its order: its node's own transform is not used.)
        const bool mirrored = matrices.skinned.empty() && glm::determinant(glm::dmat3(matrices.world)) < 0.0;
        auto emit = [&](uint32_t a, uint32_t b, uint32_t c) {
            if (mirrored) std::swap(b, c);
            scene.triangles.push_back({positions[a], positions[b], positions[c]});
            scene.materialIds.push_back(material);
            if (scene.normals.size() + 1 < scene.triangles.size()) scene.normals.resize(scene.triangles.size() - 1);
            if (!normals.empty()) {
                scene.normals.push_back({normals[a], normals[b], normals[c]});
            } else {
                // The glTF spec: without NORMAL, flat normals (as Blender's importer, three.js and
                // the Sample Viewer show them); a degenerate triangle keeps none.
                const glm::vec3 n = glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
                const float length = glm::length(n);
                const glm::vec3 flat = length > 0.0f && std::isfinite(length) ? n / length : glm::vec3(0.0f);
                scene.normals.push_back({flat, flat, flat});
            }
            if (!texcoords.empty()) {
                scene.texcoords.resize(scene.triangles.size() - 1);
                scene.texcoords.push_back({texcoords[a], texcoords[b], texcoords[c]});
            }
            if (!colors.empty()) {
                scene.colors.resize(scene.triangles.size() - 1);  // white for the triangles before
                scene.colors.push_back({colors[a], colors[b], colors[c]});
            }
            if (!tangents.empty()) {
                scene.tangents.resize(scene.triangles.size() - 1);  // none for the triangles before
                scene.tangents.push_back({tangents[a], tangents[b], tangents[c]});
            }
        };
        if (mode == TINYGLTF_MODE_TRIANGLES) {
            if (index.size() % 3 != 0) fail(at + ": " + std::to_string(index.size()) + " indices, not a multiple of 3");
            for (size_t k = 0; k + 2 < index.size(); k += 3) emit(index[k], index[k + 1], index[k + 2]);
        } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {  // the spec: p_i = (v_i, v_i+1+i%2, v_i+2-i%2)
            for (size_t k = 0; k + 2 < index.size(); ++k) emit(index[k], index[k + 1 + k % 2], index[k + 2 - k % 2]);
        } else {  // the spec: p_i = (v_i+1, v_i+2, v_0)
            for (size_t k = 0; k + 2 < index.size(); ++k) emit(index[k + 1], index[k + 2], index[0]);
        }
        // Triangles of primitives without colours white.
        if (!scene.colors.empty() && scene.colors.size() < scene.triangles.size()) scene.colors.resize(scene.triangles.size());
        // And those without tangents none (generated ones).
        if (!scene.tangents.empty() && scene.tangents.size() < scene.triangles.size()) scene.tangents.resize(scene.triangles.size());
    }

    // POSITION's values (three per vertex).
    std::vector<double> positionValues(const tinygltf::Primitive& prim,
                                       const std::string& at) const {
        if (!prim.attributes.count("POSITION")) fail(at + ": no POSITION");
        int components = 0;
        std::vector<double> p = attributeValues(prim, "POSITION", at, components);
        if (components != 3) fail(at + ": POSITION is not VEC3");
        return p;
    }

    // POSITION in world space, each finite in float.
    std::vector<glm::vec3> primitivePositions(const std::vector<double>& p, const std::string& at,
                                              const VertexMatrices& matrices) const {
        const size_t vertices = p.size() / 3;
        std::vector<glm::vec3> positions(vertices);
        for (size_t v = 0; v < vertices; ++v) {
            const glm::dvec4 w =
                matrices.of(v) * glm::dvec4(p[3 * v], p[3 * v + 1], p[3 * v + 2], 1.0);
            positions[v] = glm::vec3(w);
            if (!finite(positions[v])) fail(at + ": vertex " + std::to_string(v) + " is not finite (in float)");
        }
        return positions;
    }

    // NORMAL in world space (through the inverse transpose), unit length or 0; none without.
    std::vector<glm::vec3> primitiveNormals(const tinygltf::Primitive& prim, const std::string& at,
                                            const VertexMatrices& matrices, size_t vertices,
                                            const std::vector<double>& weights) {
        std::vector<glm::vec3> normals;
        if (!prim.attributes.count("NORMAL")) return normals;
        int components = 0;
        std::vector<double> n = attributeValues(prim, "NORMAL", at, components);
        if (components != 3 || n.size() != 3 * vertices) fail(at + ": NORMAL is not VEC3 of one per vertex");
        morph(prim, at, weights, "NORMAL", 3, n);
        const glm::dmat3 worldNormals = glm::transpose(glm::inverse(glm::dmat3(matrices.world)));
        normals.resize(vertices);
        for (size_t v = 0; v < vertices; ++v) {
            const glm::dmat3 normalMatrix =
                matrices.skinned.empty()
                    ? worldNormals
                    : glm::transpose(glm::inverse(glm::dmat3(matrices.skinned[v])));
            const glm::dvec3 w = normalMatrix * glm::dvec3(n[3 * v], n[3 * v + 1], n[3 * v + 2]);
            const double length = glm::length(w);
            normals[v] = length > 0.0 && std::isfinite(length) ? glm::vec3(w / length) : glm::vec3(0.0f);
        }
        return normals;
    }

    // The texture coordinates the base colour texture of `material` uses (TEXCOORD_n of
    // textureInfo.texCoord), not finite ones as 0; none for an untextured material or (with a
    // warning) a primitive without that set.
    std::vector<glm::vec2> primitiveTexcoords(const tinygltf::Primitive& prim, const std::string& at, uint32_t material,
                                              size_t vertices) const {
        std::vector<glm::vec2> texcoords;
        if (material >= uvs_.size() || uvs_[material].set < 0) return texcoords;
        const MaterialUv& uv = uvs_[material];
        const std::string set = "TEXCOORD_" + std::to_string(uv.set);
        if (!prim.attributes.count(set)) {
            warn(at + ": no " + set + " for its material's texture; it is sampled at (0, 0)");
            return texcoords;
        }
        int components = 0;
        const std::vector<double> t = attributeValues(prim, set, at, components);
        if (components != 2 || t.size() != 2 * vertices) fail(at + ": " + set + " is not VEC2 of one per vertex");
        texcoords.resize(vertices);
        for (size_t v = 0; v < vertices; ++v) {
            const glm::dvec3 mapped = uv.transform * glm::dvec3(t[2 * v], t[2 * v + 1], 1.0);
            const glm::vec2 c{float(mapped.x), float(mapped.y)};
            texcoords[v] = std::isfinite(c.x) && std::isfinite(c.y) ? c : glm::vec2(0.0f);
        }
        return texcoords;
    }

    // COLOR_0, linear RGB (the spec's vertex colours, which multiply the base colour): VEC3 or VEC4
    // of FLOAT or normalized UNSIGNED_BYTE / UNSIGNED_SHORT, values outside [0, 1] clamped with a
    // warning. The alpha of VEC4 is not used (a warning when it is not 1 everywhere). None
    // without, or (with a warning) of another component type.
    std::vector<glm::vec3> primitiveColors(const tinygltf::Primitive& prim, const std::string& at, size_t vertices) const {
        std::vector<glm::vec3> colors;
        const auto attribute = prim.attributes.find("COLOR_0");
        if (attribute == prim.attributes.end()) return colors;
        const int index = attribute->second;
        if (index < 0 || index >= int(m_.accessors.size())) fail(at + ": accessor " + std::to_string(index) + " does not exist");
        const tinygltf::Accessor& a = m_.accessors[size_t(index)];
        const bool known = a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                           (a.normalized && (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                             a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
        if (!known) {
            warn(at + ": COLOR_0 of component type " + std::to_string(a.componentType) +
                 " (not FLOAT or normalized UNSIGNED_BYTE or UNSIGNED_SHORT) is not used");
            return colors;
        }
        int components = 0;
        const std::vector<double> c = attributeValues(prim, "COLOR_0", at, components);  // Draco or the accessor
        if ((components != 3 && components != 4) || c.size() != size_t(components) * vertices)
            fail(at + ": COLOR_0 is not VEC3 or VEC4 of one per vertex");
        colors.resize(vertices);
        bool alpha = false, outside = false;
        for (size_t v = 0; v < vertices; ++v) {
            const double* e = &c[v * size_t(components)];
            for (int k = 0; k < 3; ++k) {
                const bool in = e[k] >= 0.0 && e[k] <= 1.0;
                outside = outside || !in;
                colors[v][k] = in ? float(e[k]) : e[k] > 1.0 ? 1.0f : 0.0f;  // NaN: 0
            }
            alpha = alpha || (components == 4 && e[3] != 1.0);
        }
        if (outside) warn(at + ": COLOR_0 values outside [0, 1] clamped");
        if (alpha) warn(at + ": the alpha of COLOR_0 is not used (only its RGB multiplies the base colour)");
        return colors;
    }

    // TANGENT in world space, for the normal map or the anisotropy of the primitive's material: VEC4 of FLOAT or of
    // normalized BYTE / SHORT (KHR_mesh_quantization), from its Draco data when compressed; any
    // other type or count is an error. xyz goes through the linear part of the node's (or the
    // skinned vertex's) transform and is normalised, zero where it is zero or not finite (such
    // corners fall back to generated tangents, glsl/common/shading.h normalMappedTangent); w is
    // its sign (0 and NaN: +1), turned over by a mirroring transform (as the bitangent
    // cross(normal, tangent) * w must follow the mirror image). None without TANGENT or for a
    // material without a normal map or anisotropy (the texture coordinates' sets the materials do
    // not use are not named either), and none, with a warning, without NORMAL (the spec: tangents
    // are then ignored, as the normals are made flat).
    std::vector<glm::vec4> primitiveTangents(const tinygltf::Primitive& prim, const std::string& at,
                                             const VertexMatrices& matrices, size_t vertices, uint32_t material,
                                             const std::vector<glm::vec3>& normals, const std::vector<double>& weights,
                                             const Scene& scene) {
        std::vector<glm::vec4> tangents;
        const auto attribute = prim.attributes.find("TANGENT");
        const Material& m = scene.materials[material];
        if (attribute == prim.attributes.end() || (m.normalTexture < 0 && !m.hasAnisotropy())) return tangents;
        if (normals.empty()) {
            warnOnce("TANGENT without NORMAL",
                     at + ": TANGENT is not used (no NORMAL: glTF ignores tangents then; the normal map uses "
                          "tangents generated per triangle)");
            return tangents;
        }
        const int index = attribute->second;
        if (index < 0 || index >= int(m_.accessors.size()))
            fail(at + " TANGENT: accessor " + std::to_string(index) + " does not exist");
        const tinygltf::Accessor& a = m_.accessors[size_t(index)];
        const bool known = a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                           (a.normalized && (a.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
                                             a.componentType == TINYGLTF_COMPONENT_TYPE_SHORT));
        if (!known)
            fail(at + ": TANGENT (accessor " + std::to_string(index) + ") of component type " +
                 std::to_string(a.componentType) + " (not FLOAT or normalized BYTE or SHORT)");
        int components = 0;
        std::vector<double> t = attributeValues(prim, "TANGENT", at, components);  // Draco or the accessor
        if (components != 4 || t.size() != 4 * vertices)
            fail(at + ": TANGENT (accessor " + std::to_string(index) + ") is not VEC4 of one per vertex");
        morph(prim, at, weights, "TANGENT", 4, t);  // the targets' TANGENT are VEC3 (xyz)
        const glm::dmat3 worldTangents(matrices.world);
        const double worldHand = glm::determinant(worldTangents) < 0.0 ? -1.0 : 1.0;
        tangents.resize(vertices);
        for (size_t v = 0; v < vertices; ++v) {
            const glm::dmat3 m = matrices.skinned.empty() ? worldTangents : glm::dmat3(matrices.skinned[v]);
            const double hand = matrices.skinned.empty() ? worldHand : glm::determinant(m) < 0.0 ? -1.0 : 1.0;
            const glm::dvec3 w = m * glm::dvec3(t[4 * v], t[4 * v + 1], t[4 * v + 2]);
            const double length = glm::length(w);
            const glm::vec3 unit = length > 0.0 && std::isfinite(length) ? glm::vec3(w / length) : glm::vec3(0.0f);
            tangents[v] = glm::vec4(unit, float((t[4 * v + 3] < 0.0 ? -1.0 : 1.0) * hand));
        }
        return tangents;
    }

    // A primitive of an anisotropic material without TANGENT (with NORMAL) and without texture
    // coordinates, which KHR_materials_anisotropy does not allow: its tangent runs around the up axis
    // (glsl/common/shading.h anisotropyFrameDirection).
    void warnNoTangentFrame(const std::string& at) {
        warnOnce("anisotropy without a frame " + at,
                 at + ": no TANGENT (with NORMAL) and no texture coordinates of the material's textures for "
                      "KHR_materials_anisotropy's tangent frame: its direction runs around the up axis");
    }

    // The primitive's indices (unsigned integers below `vertices`), or 0, 1, ... without.
    std::vector<uint32_t> primitiveIndices(const tinygltf::Primitive& prim, const std::string& at, size_t vertices) const {
        std::vector<uint32_t> index;
        if (const DracoPrimitive* draco = dracoOf(prim, at)) {
            for (uint32_t i : draco->mesh.indices)
                if (i >= vertices)
                    fail(at + ": Draco face index " + std::to_string(i) + " out of range (" +
                         std::to_string(vertices) + " vertices)");
            return draco->mesh.indices;
        }
        if (prim.indices < 0) {
            index.resize(vertices);
            for (size_t v = 0; v < vertices; ++v) index[v] = uint32_t(v);
            return index;
        }
        if (prim.indices >= int(m_.accessors.size())) fail(at + ": accessor " + std::to_string(prim.indices) + " does not exist");
        const tinygltf::Accessor& a = m_.accessors[size_t(prim.indices)];
        if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            fail(at + ": indices of component type " + std::to_string(a.componentType) + " (not an unsigned integer)");
        int components = 0;
        const std::vector<double> i = values(prim.indices, at + " indices", components);
        if (components != 1) fail(at + ": indices are not SCALAR");
        index.reserve(i.size());
        for (double v : i) {
            if (v >= double(vertices))
                fail(at + ": index " + std::to_string(uint64_t(v)) + " out of range (" + std::to_string(vertices) + " vertices)");
            index.push_back(uint32_t(v));
        }
        return index;
    }

    static double number(const tinygltf::Value& object, const char* key, double fallback) {
        if (!object.IsObject() || !object.Has(key)) return fallback;
        const tinygltf::Value& v = object.Get(key);
        return v.IsNumber() || v.IsInt() || v.IsReal() ? v.GetNumberAsDouble() : fallback;
    }

    // The scene material of glTF material `index` (made at its first use; -1: gpurt's default).
    uint32_t materialOf(int index, Scene& scene) {
        if (index < 0) return 0;
        if (index >= int(m_.materials.size())) fail("material " + std::to_string(index) + " does not exist");
        if (materialIds_[size_t(index)] >= 0) return uint32_t(materialIds_[size_t(index)]);
        const std::string at = "material " + std::to_string(index);
        const tinygltf::Material g = metallicRoughnessOf(m_.materials[size_t(index)], at);
        const std::vector<double>& base = g.pbrMetallicRoughness.baseColorFactor;
        if (base.size() != 4) fail(at + ": baseColorFactor is not 4 numbers");
        const glm::vec3 colour{float(base[0]), float(base[1]), float(base[2])};
        const double metallic = g.pbrMetallicRoughness.metallicFactor, roughness = g.pbrMetallicRoughness.roughnessFactor;
        auto inUnit = [](double v) { return v >= 0.0 && v <= 1.0; };
        if (!inUnit(base[0]) || !inUnit(base[1]) || !inUnit(base[2]) || !inUnit(metallic) || !inUnit(roughness))
            fail(at + ": baseColorFactor, metallicFactor and roughnessFactor must be in [0, 1]");
        Material m;
        m.name = g.name.empty() ? at : g.name;
        m.model = GPURT_MODEL_GLTF;  // Appendix B's BRDF
        m.emissionIsLight = false;  // it glows; the default light stays (CONTRACT.md, "Lights")
        m.diffuse = colour;
        m.metallic = float(metallic);
        m.roughness = float(roughness);
        m.specular = glm::vec3(0.0f);
        glm::dvec3 emissive(0.0);
        if (g.emissiveFactor.size() == 3) emissive = glm::dvec3(g.emissiveFactor[0], g.emissiveFactor[1], g.emissiveFactor[2]);
        const auto strength = g.extensions.find("KHR_materials_emissive_strength");
        if (strength != g.extensions.end()) emissive *= number(strength->second, "emissiveStrength", 1.0);
        m.emission = glm::vec3(emissive);
        if (g.extensions.count("KHR_materials_unlit") > 0) return readUnlit(g, at, m, scene, index);
        readIorAndTransmission(g, at, m);
        if (!finite(m.emission) || glm::any(glm::lessThan(m.emission, glm::vec3(0.0f))) || !std::isfinite(m.ior) ||
            m.ior < 0.0f || (m.ior > 0.0f && m.ior < 1.0f))
            fail(at + ": emission must be finite and >= 0, ior >= 1");
        // The texture slots; all share the texture coordinates of the first one used (its
        // TEXCOORD_n and KHR_texture_transform), a slot that asks for others is warned about.
        MaterialUv uv;
        const std::string named = at + " ('" + m.name + "')";
        const tinygltf::TextureInfo& baseTexture = g.pbrMetallicRoughness.baseColorTexture;
        if (baseTexture.index >= 0 && (m.diffuse != glm::vec3(0.0f) || m.model == GPURT_MODEL_GLTF))
            m.diffuseTexture = slot(baseTexture.index, baseTexture.texCoord, baseTexture.extensions, "baseColorTexture", named, uv, scene);
        readMaps(g, at, named, m, uv, scene);
        // Material extensions gpurt does not read are warned about once per file with the
        // other unread extensions (kExtensionsRead).
        readAlpha(g, baseTexture, named, m, uv, scene);
        readGlossiness(m_.materials[size_t(index)], named, m, uv, scene);
        m.doubleSided = g.doubleSided;  // glTF's default: single-sided (back faces culled)
        uvs_.resize(scene.materials.size() + 1);
        uvs_.back() = uv;
        scene.materials.push_back(m);
        materialIds_[size_t(index)] = int(scene.materials.size() - 1);
        return uint32_t(scene.materials.size() - 1);
    }

    // KHR_materials_pbrSpecularGlossiness (archived, in many older files) as the metallic-roughness
    // model with KHR_materials_specular, the conversion Khronos' tools make (glTF-Transform's
    // metalRough): base colour = diffuseFactor (its alpha too) and diffuseTexture, metallic 0,
    // roughness 1 - glossinessFactor, and a specular layer of F0 = specularFactor x the RGB of
    // specularGlossinessTexture (sRGB): specular colour = specularFactor / 0.04 over ior 1.5's F0.
    // The glossiness map (A) is readGlossiness's. A material with both the extension and
    // pbrMetallicRoughness uses the extension (the metallic-roughness values are its fallback).
    // What differs from the archived extension's own BRDF: the diffuse under the specular is
    // weighed by 1 - max(F(v.h)) (fresnel_mix) rather than 1 - max(F0).
    tinygltf::Material metallicRoughnessOf(const tinygltf::Material& source, const std::string& at) {
        const auto found = source.extensions.find("KHR_materials_pbrSpecularGlossiness");
        if (found == source.extensions.end()) return source;
        const tinygltf::Value& ext = found->second;
        tinygltf::Material g = source;
        std::vector<double> diffuse = {1.0, 1.0, 1.0, 1.0};
        if (ext.IsObject() && ext.Has("diffuseFactor")) {
            const tinygltf::Value& d = ext.Get("diffuseFactor");
            if (!d.IsArray() || d.ArrayLen() != 4) fail(at + ": diffuseFactor is not 4 numbers");
            for (int k = 0; k < 4; ++k) {
                diffuse[size_t(k)] = d.Get(k).IsNumber() ? d.Get(k).GetNumberAsDouble() : -1.0;
                if (!(diffuse[size_t(k)] >= 0.0 && diffuse[size_t(k)] <= 1.0)) fail(at + ": diffuseFactor must be 4 numbers in [0, 1]");
            }
        }
        const glm::vec3 specular = colourFactor(ext, "specularFactor", glm::vec3(1.0f), 1.0, at);
        const double glossiness = number(ext, "glossinessFactor", 1.0);
        if (!(glossiness >= 0.0 && glossiness <= 1.0)) fail(at + ": glossinessFactor must be in [0, 1]");
        g.pbrMetallicRoughness = tinygltf::PbrMetallicRoughness();
        g.pbrMetallicRoughness.baseColorFactor = diffuse;
        g.pbrMetallicRoughness.metallicFactor = 0.0;
        g.pbrMetallicRoughness.roughnessFactor = 1.0 - glossiness;
        if (ext.IsObject() && ext.Has("diffuseTexture")) textureInfoOf(ext.Get("diffuseTexture"), at + ": diffuseTexture", g.pbrMetallicRoughness.baseColorTexture);
        if (g.extensions.count("KHR_materials_specular") == 0) {
            tinygltf::Value::Object layer;
            tinygltf::Value::Array colour;
            for (int k = 0; k < 3; ++k) colour.emplace_back(double(specular[k]) / 0.04);
            layer["specularColorFactor"] = tinygltf::Value(colour);
            if (ext.IsObject() && ext.Has("specularGlossinessTexture"))
                layer["specularColorTexture"] = ext.Get("specularGlossinessTexture");
            g.extensions["KHR_materials_specular"] = tinygltf::Value(layer);
        }
        return g;
    }

    // A textureInfo (index, texCoord, extensions) inside an extension, as tinygltf reads the core
    // ones; `what` names it in refusals.
    void textureInfoOf(const tinygltf::Value& info, const std::string& what, tinygltf::TextureInfo& out) {
        int index = -1, texCoord = 0;
        if (!info.IsObject() || !info.Has("index") || !wholeNumber(info.Get("index"), index) || index < 0)
            fail(what + " has no texture index");
        if (info.Has("texCoord") && !wholeNumber(info.Get("texCoord"), texCoord)) fail(what + " texCoord is not a whole number");
        out.index = index;
        out.texCoord = texCoord;
        if (info.Has("extensions") && info.Get("extensions").IsObject()) {
            const tinygltf::Value& e = info.Get("extensions");
            for (const std::string& k : e.Keys()) out.extensions[k] = e.Get(k);
        }
    }

    // KHR_materials_ior: the dielectric's F0; KHR_materials_transmission: a rough dielectric
    // solid (glsl/common/materials/gltf.h; record ior > 0 with transmission t in all channels).
    void readIorAndTransmission(const tinygltf::Material& g, const std::string& at, Material& m) {
        auto inUnit = [](double v) { return v >= 0.0 && v <= 1.0; };
        m.transmission = glm::vec3(0.0f);
        const auto ior = g.extensions.find("KHR_materials_ior");
        if (ior != g.extensions.end()) {
            const double eta = number(ior->second, "ior", 1.5);
            if (eta == 0.0) {
                warn(at + ": KHR_materials_ior 0 (F0 = 1) is not supported; ior 1.5 is used");
            } else {
                if (!std::isfinite(eta) || eta < 1.0 || eta > 1e3) fail(at + ": KHR_materials_ior ior must be in [1, 1000] or 0");
                m.ior = float(eta);
            }
        }
        const auto transmission = g.extensions.find("KHR_materials_transmission");
        if (transmission != g.extensions.end()) {
            const double t = number(transmission->second, "transmissionFactor", 0.0);
            if (!inUnit(t)) fail(at + ": transmissionFactor must be in [0, 1]");
            if (t > 0.0) {
                if (!(m.ior > 0.0f)) m.ior = 1.5f;
                m.transmission = glm::vec3(float(t));
                const auto volume = g.extensions.find("KHR_materials_volume");
                // Without KHR_materials_volume (or with its thicknessFactor 0) the surface is a thin wall.
                m.thinWalled = volume == g.extensions.end() || !(number(volume->second, "thicknessFactor", 0.0) > 0.0);
            }
        }
    }

    // KHR_materials_unlit (glsl/common/material.h GPURT_MODEL_UNLIT): the base colour, its texture
    // and alpha; what else the material holds is a warning.
    uint32_t readUnlit(const tinygltf::Material& g, const std::string& at, Material& m, Scene& scene, int index) {
        m.model = GPURT_MODEL_UNLIT;
        const std::string named = at + " ('" + m.name + "')";
        if (m.emits()) warn(named + ": the emission of an unlit material is not used");
        m.emission = glm::vec3(0.0f);
        for (const char* other : {"KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_emissive_strength",
                                  "KHR_materials_clearcoat", "KHR_materials_specular", "KHR_materials_sheen"})
            if (g.extensions.count(other) > 0) warn(named + ": " + other + " of an unlit material is not used");
        if (g.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0 || g.normalTexture.index >= 0 ||
            g.occlusionTexture.index >= 0 || g.emissiveTexture.index >= 0)
            warn(named + ": the textures of an unlit material other than baseColorTexture are not used");
        MaterialUv uv;
        const tinygltf::TextureInfo& baseTexture = g.pbrMetallicRoughness.baseColorTexture;
        if (baseTexture.index >= 0)
            m.diffuseTexture = slot(baseTexture.index, baseTexture.texCoord, baseTexture.extensions, "baseColorTexture", named, uv, scene);
        readAlpha(g, baseTexture, named, m, uv, scene);
        m.doubleSided = g.doubleSided;
        uvs_.resize(scene.materials.size() + 1);
        uvs_.back() = uv;
        scene.materials.push_back(m);
        materialIds_[size_t(index)] = int(scene.materials.size() - 1);
        return uint32_t(scene.materials.size() - 1);
    }

    // The texture coordinates a material's textures share: TEXCOORD_set (-1: no texture) mapped
    // by KHR_texture_transform's matrix (offset + rotation + scale, in glTF's u right, v down).
    struct MaterialUv {
        int set = -1;
        glm::dmat3 transform{1.0};
        std::string slot;  // the slot that chose them
    };

    // The metallic-roughness, normal, emissive, occlusion and transmission maps (the base colour's
    // and alpha's are read apart), each through `uv`, the material's shared coordinates.
    void readMaps(const tinygltf::Material& g, const std::string& at, const std::string& named, Material& m,
                  MaterialUv& uv, Scene& scene) {
        auto inUnit = [](double v) { return v >= 0.0 && v <= 1.0; };
        const tinygltf::TextureInfo& mr = g.pbrMetallicRoughness.metallicRoughnessTexture;
        if (mr.index >= 0) {
            const int tex = slot(mr.index, mr.texCoord, mr.extensions, "metallicRoughnessTexture", named, uv, scene);
            if (tex >= 0) {
                m.roughnessTexture = {tex, 1};  // G
                m.metallicTexture = {tex, 2};   // B
            }
        }
        const tinygltf::NormalTextureInfo& normal = g.normalTexture;
        if (normal.index >= 0) {
            m.normalTexture = slot(normal.index, normal.texCoord, normal.extensions, "normalTexture", named, uv, scene);
            m.normalScale = float(normal.scale);
            if (!std::isfinite(m.normalScale)) fail(at + ": normalTexture scale must be finite");
        }
        const tinygltf::TextureInfo& glow = g.emissiveTexture;
        if (glow.index >= 0 && m.emits())
            m.emissiveTexture = slot(glow.index, glow.texCoord, glow.extensions, "emissiveTexture", named, uv, scene);
        const tinygltf::OcclusionTextureInfo& occlusion = g.occlusionTexture;
        if (occlusion.index >= 0) {
            const int tex = slot(occlusion.index, occlusion.texCoord, occlusion.extensions, "occlusionTexture", named, uv, scene);
            if (tex >= 0) m.occlusionTexture = {tex, 0};  // R
            m.occlusionStrength = float(occlusion.strength);
            if (!inUnit(occlusion.strength)) fail(at + ": occlusionTexture strength must be in [0, 1]");
        }
        if (m.transmits()) readTransmissionTexture(g, named, m, uv, scene);
        readSpecular(g, at, named, m, uv, scene);
        readClearcoat(g, at, named, m, uv, scene);
        readSheen(g, at, named, m, uv, scene);
        readVolume(g, at, named, m);
        readDispersion(g, at, named, m);
        readIridescence(g, at, named, m, uv, scene);
        readAnisotropy(g, at, named, m, uv, scene);
    }

    // KHR_materials_pbrSpecularGlossiness's glossiness map, the A of specularGlossinessTexture
    // (linear): roughness = 1 - glossinessFactor x A, read from a texture made from it whose A is
    // that roughness (8 bits, exact for the default factor 1), through the material's coordinates.
    void readGlossiness(const tinygltf::Material& source, const std::string& named, Material& m, MaterialUv& uv,
                        Scene& scene) {
        const auto found = source.extensions.find("KHR_materials_pbrSpecularGlossiness");
        if (found == source.extensions.end()) return;
        const int gloss = extensionTexture(found->second, "specularGlossinessTexture", named, uv, scene);
        if (gloss < 0) return;
        const float factor = float(number(found->second, "glossinessFactor", 1.0));  // checked by metallicRoughnessOf
        const std::pair<int, float> key(gloss, factor);
        auto made = roughnessFromGloss_.find(key);
        if (made == roughnessFromGloss_.end()) {
            Texture rough = scene.textures[size_t(gloss)];
            rough.name += " (roughness = 1 - " + std::to_string(factor) + " x glossiness)";
            for (uint32_t& t : rough.image.texels) {
                const float a = float(t >> 24) / 255.0f;
                t = (t & 0xffffffu) | (uint32_t(std::lround((1.0f - factor * a) * 255.0f)) << 24);
            }
            scene.textures.push_back(std::move(rough));
            made = roughnessFromGloss_.emplace(key, int(scene.textures.size() - 1)).first;
        }
        m.roughness = 1.0f;
        m.roughnessTexture = {made->second, 3};  // A
    }

    // KHR_materials_iridescence (glsl/common/materials/gltf.h thinFilmFresnel): the film's weight
    // (iridescenceFactor times iridescenceTexture's R), index, and thickness from its minimum to its
    // maximum by iridescenceThicknessTexture's G (the maximum without it); factor 0: no film, its
    // maps unread.
    void readIridescence(const tinygltf::Material& g, const std::string& at, const std::string& named, Material& m,
                         MaterialUv& uv, Scene& scene) {
        const auto found = g.extensions.find("KHR_materials_iridescence");
        if (found == g.extensions.end()) return;
        const tinygltf::Value& ext = found->second;
        const double factor = number(ext, "iridescenceFactor", 0.0), ior = number(ext, "iridescenceIor", 1.3);
        const double lo = number(ext, "iridescenceThicknessMinimum", 100.0), hi = number(ext, "iridescenceThicknessMaximum", 400.0);
        if (!(factor >= 0.0 && factor <= 1.0)) fail(at + ": iridescenceFactor must be in [0, 1]");
        if (!(ior >= 1.0 && ior <= 1e3)) fail(at + ": iridescenceIor must be in [1, 1000]");
        if (!(lo >= 0.0 && lo <= 1e6) || !(hi >= 0.0 && hi <= 1e6))
            fail(at + ": iridescenceThicknessMinimum and iridescenceThicknessMaximum must be in [0, 1e6] nm");
        m.iridescenceFactor = float(factor);
        m.iridescenceIor = float(ior);
        m.iridescenceThicknessMin = float(lo);
        m.iridescenceThicknessMax = float(hi);
        if (!(factor > 0.0)) return;
        const int weight = extensionTexture(ext, "iridescenceTexture", named, uv, scene);
        if (weight >= 0) m.iridescenceTexture = {weight, 0};  // R
        const int thickness = extensionTexture(ext, "iridescenceThicknessTexture", named, uv, scene);
        if (thickness >= 0) m.iridescenceThicknessTexture = {thickness, 1};  // G
    }

    // KHR_materials_anisotropy (glsl/common/materials/gltf.h gltfAnisotropyAt): the strength in
    // [0, 1], the rotation (radians, finite) and anisotropyTexture (linear RGB: the direction in RG,
    // the strength's factor in B); strength 0: isotropic, the map unread. The direction lies in the
    // tangent frame (primitiveTangents, or the texture coordinates'; a primitive with neither, which
    // the extension does not allow, is a warning: its tangent runs around the up axis).
    void readAnisotropy(const tinygltf::Material& g, const std::string& at, const std::string& named, Material& m,
                        MaterialUv& uv, Scene& scene) {
        const auto found = g.extensions.find("KHR_materials_anisotropy");
        if (found == g.extensions.end()) return;
        const tinygltf::Value& ext = found->second;
        const double strength = number(ext, "anisotropyStrength", 0.0), rotation = number(ext, "anisotropyRotation", 0.0);
        if (!(strength >= 0.0 && strength <= 1.0)) fail(at + ": anisotropyStrength must be in [0, 1]");
        if (!std::isfinite(rotation)) fail(at + ": anisotropyRotation must be finite");
        m.anisotropyStrength = float(strength);
        m.anisotropyRotation = float(rotation);
        if (strength > 0.0) m.anisotropyTexture = extensionTexture(ext, "anisotropyTexture", named, uv, scene);
    }

    // KHR_materials_volume (glsl/common/material.h materialTransmittance): the thickness (0: a thin
    // wall) and the attenuation (attenuationColor, attenuationDistance > 0, infinite by default).
    // The rays measure the distance they travel inside, so thicknessTexture is a warning.
    void readVolume(const tinygltf::Material& g, const std::string& at, const std::string& named, Material& m) {
        const auto found = g.extensions.find("KHR_materials_volume");
        if (found == g.extensions.end()) return;
        const tinygltf::Value& ext = found->second;
        const double thickness = number(ext, "thicknessFactor", 0.0);
        if (!(thickness >= 0.0 && std::isfinite(thickness))) fail(at + ": thicknessFactor must be a number >= 0");
        m.thickness = float(thickness);
        m.attenuationColor = colourFactor(ext, "attenuationColor", m.attenuationColor, 1.0, at);
        const double distance = number(ext, "attenuationDistance", double(m.attenuationDistance));
        if (!(distance > 0.0)) fail(at + ": attenuationDistance must be a number > 0");
        m.attenuationDistance = float(distance);
        if (ext.IsObject() && ext.Has("thicknessTexture"))
            warn(named + ": KHR_materials_volume's thicknessTexture is not used (rays measure the distance inside)");
    }

    // KHR_materials_dispersion (glsl/common/material.h dispersedIor): 20 / the Abbe number, >= 0.
    // The extension applies to volumes only: on a material without transmission and a volume it
    // changes nothing, which a warning says.
    void readDispersion(const tinygltf::Material& g, const std::string& at, const std::string& named, Material& m) {
        const auto found = g.extensions.find("KHR_materials_dispersion");
        if (found == g.extensions.end()) return;
        const double dispersion = number(found->second, "dispersion", 0.0);
        if (!(dispersion >= 0.0 && dispersion <= 1e3)) fail(at + ": dispersion must be a number in [0, 1000]");
        m.dispersion = float(dispersion);
        if (m.dispersion > 0.0f && !m.disperses())
            warn(named + ": KHR_materials_dispersion is not used: it applies to transmissive volumes only "
                         "(KHR_materials_transmission and KHR_materials_volume)");
    }

    // KHR_materials_sheen (glsl/common/materials/gltf.h sheenLobe): the sheen's colour
    // (sheenColorFactor times sheenColorTexture, sRGB) and roughness (sheenRoughnessFactor times
    // sheenRoughnessTexture's A); a black colour is no sheen, its maps unread.
    void readSheen(const tinygltf::Material& g, const std::string& at, const std::string& named, Material& m,
                   MaterialUv& uv, Scene& scene) {
        const auto found = g.extensions.find("KHR_materials_sheen");
        if (found == g.extensions.end()) return;
        const tinygltf::Value& ext = found->second;
        m.sheenColor = colourFactor(ext, "sheenColorFactor", m.sheenColor, 1.0, at);
        const double roughness = number(ext, "sheenRoughnessFactor", 0.0);
        if (!(roughness >= 0.0 && roughness <= 1.0)) fail(at + ": sheenRoughnessFactor must be in [0, 1]");
        m.sheenRoughness = float(roughness);
        if (!m.hasSheen()) return;
        m.sheenColorTexture = extensionTexture(ext, "sheenColorTexture", named, uv, scene);
        const int rough = extensionTexture(ext, "sheenRoughnessTexture", named, uv, scene);
        if (rough >= 0) m.sheenRoughnessTexture = {rough, 3};  // A
    }

    // A material extension's colour factor `key` (3 numbers in [0, max]; `fallback` without it),
    // refused naming the material (`at`) otherwise.
    glm::vec3 colourFactor(const tinygltf::Value& ext, const char* key, glm::vec3 fallback, double max,
                           const std::string& at) {
        if (!ext.IsObject() || !ext.Has(key)) return fallback;
        const tinygltf::Value& c = ext.Get(key);
        if (!c.IsArray() || c.ArrayLen() != 3) fail(at + ": " + key + " is not 3 numbers");
        glm::vec3 colour;
        for (int k = 0; k < 3; ++k) {
            const tinygltf::Value& v = c.Get(k);
            const double x = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
            if (!(x >= 0.0 && x <= max)) {
                char limit[32];
                std::snprintf(limit, sizeof limit, "%g", max);
                fail(at + ": " + key + " must be 3 numbers in [0, " + limit + "]");
            }
            colour[k] = float(x);
        }
        return colour;
    }

    // KHR_materials_specular (glsl/common/materials/gltf.h gltfDielectricLayer): the specular
    // layer's weight (specularFactor times specularTexture's A) and F0 colour (specularColorFactor
    // times specularColorTexture, sRGB).
    void readSpecular(const tinygltf::Material& g, const std::string& at, const std::string& named, Material& m,
                      MaterialUv& uv, Scene& scene) {
        const auto found = g.extensions.find("KHR_materials_specular");
        if (found == g.extensions.end()) return;
        const tinygltf::Value& ext = found->second;
        const double factor = number(ext, "specularFactor", 1.0);
        if (!(factor >= 0.0 && factor <= 1.0)) fail(at + ": specularFactor must be in [0, 1]");
        m.specularFactor = float(factor);
        m.specularColor = colourFactor(ext, "specularColorFactor", m.specularColor, 1e3, at);
        const int weight = extensionTexture(ext, "specularTexture", named, uv, scene);
        if (weight >= 0) m.specularTexture = {weight, 3};  // A
        m.specularColorTexture = extensionTexture(ext, "specularColorTexture", named, uv, scene);
    }

    // KHR_materials_clearcoat (glsl/common/materials/gltf.h gltfCoatWeight): the coat's weight
    // (clearcoatFactor times clearcoatTexture's R), roughness (clearcoatRoughnessFactor times
    // clearcoatRoughnessTexture's G) and normal map; a factor of 0 is no coat, its maps unread.
    void readClearcoat(const tinygltf::Material& g, const std::string& at, const std::string& named, Material& m,
                       MaterialUv& uv, Scene& scene) {
        const auto found = g.extensions.find("KHR_materials_clearcoat");
        if (found == g.extensions.end()) return;
        const tinygltf::Value& ext = found->second;
        const double factor = number(ext, "clearcoatFactor", 0.0), roughness = number(ext, "clearcoatRoughnessFactor", 0.0);
        if (!(factor >= 0.0 && factor <= 1.0) || !(roughness >= 0.0 && roughness <= 1.0))
            fail(at + ": clearcoatFactor and clearcoatRoughnessFactor must be in [0, 1]");
        m.clearcoat = float(factor);
        m.clearcoatRoughness = float(roughness);
        if (!m.hasClearcoat()) return;
        const int weight = extensionTexture(ext, "clearcoatTexture", named, uv, scene);
        if (weight >= 0) m.clearcoatTexture = {weight, 0};  // R
        const int rough = extensionTexture(ext, "clearcoatRoughnessTexture", named, uv, scene);
        if (rough >= 0) m.clearcoatRoughnessTexture = {rough, 1};  // G
        double scale = 1.0;
        m.clearcoatNormalTexture = extensionTexture(ext, "clearcoatNormalTexture", named, uv, scene, &scale);
        m.clearcoatNormalScale = float(scale);
        if (!std::isfinite(m.clearcoatNormalScale)) fail(at + ": clearcoatNormalTexture scale must be finite");
    }

    // KHR_materials_transmission's transmissionTexture: its R channel times the factor.
    void readTransmissionTexture(const tinygltf::Material& g, const std::string& named, Material& m, MaterialUv& uv,
                                 Scene& scene) {
        const int tex = extensionTexture(g.extensions.at("KHR_materials_transmission"), "transmissionTexture", named, uv, scene);
        if (tex >= 0) m.transmissionTexture = {tex, 0};  // R
    }

    // The texture of a textureInfo `key` inside a material extension (tinygltf leaves it as JSON),
    // with its texCoord and KHR_texture_transform as every slot's; -1 when the extension has none.
    // `scale`: a normalTextureInfo's scale (1 when absent). An index that is no whole number >= 0,
    // or a texCoord that is no whole number, is refused naming the material.
    int extensionTexture(const tinygltf::Value& ext, const char* key, const std::string& named, MaterialUv& uv,
                         Scene& scene, double* scale = nullptr) {
        if (!ext.IsObject() || !ext.Has(key)) return -1;
        const tinygltf::Value& info = ext.Get(key);
        int index = -1, texCoord = 0;
        if (!info.IsObject() || !info.Has("index") || !wholeNumber(info.Get("index"), index) || index < 0)
            fail(named + ": " + key + " has no texture index");
        if (info.Has("texCoord") && !wholeNumber(info.Get("texCoord"), texCoord))
            fail(named + ": " + key + " texCoord is not a whole number");
        if (scale) *scale = number(info, "scale", 1.0);
        tinygltf::ExtensionMap extensions;
        if (info.Has("extensions") && info.Get("extensions").IsObject()) {
            const tinygltf::Value& e = info.Get("extensions");
            for (const std::string& k : e.Keys()) extensions[k] = e.Get(k);
        }
        return slot(index, texCoord, extensions, key, named, uv, scene);
    }

    // alphaMode MASK / BLEND: alpha is baseColorFactor[3] times baseColorTexture's A (the base
    // colour's texture slot when the material has one), MASK's alphaCutoff in [0, 1].
    void readAlpha(const tinygltf::Material& g, const tinygltf::TextureInfo& baseTexture, const std::string& named,
                   Material& m, MaterialUv& uv, Scene& scene) {
        if (g.alphaMode.empty() || g.alphaMode == "OPAQUE") return;
        if (g.alphaMode != "MASK" && g.alphaMode != "BLEND") {
            warn(named + ": alphaMode " + g.alphaMode + " is not OPAQUE, MASK or BLEND; the material is opaque");
            return;
        }
        const double alpha = g.pbrMetallicRoughness.baseColorFactor[3];
        if (!(alpha >= 0.0 && alpha <= 1.0)) fail(named + ": baseColorFactor's alpha must be in [0, 1]");
        m.alphaMode = g.alphaMode == "MASK" ? 1 : 2;  // glsl/common/alpha.h GPURT_ALPHA_MASK, _BLEND
        m.alphaFactor = float(alpha);
        if (m.alphaMode == 1) {
            if (!(g.alphaCutoff >= 0.0 && g.alphaCutoff <= 1.0))
                fail(named + ": alphaCutoff " + std::to_string(g.alphaCutoff) + " must be in [0, 1]");
            m.alphaCutoff = float(g.alphaCutoff);
        }
        int tex = m.diffuseTexture;
        if (tex < 0 && baseTexture.index >= 0)
            tex = slot(baseTexture.index, baseTexture.texCoord, baseTexture.extensions, "baseColorTexture", named, uv, scene);
        if (tex >= 0) m.alphaTexture = {tex, 3};  // A
    }

    // The scene texture of one texture slot of a material (-1 with a warning when its image could
    // not be read); the first slot fixes the material's texture coordinates (uv).
    int slot(int index, int texCoord, const tinygltf::ExtensionMap& extensions, const char* name, const std::string& material,
             MaterialUv& uv, Scene& scene) {
        if (texCoord < 0 || texCoord > 255) fail(material + ": " + name + " texCoord " + std::to_string(texCoord) + " out of range");
        int set = texCoord;
        glm::dmat3 transform(1.0);
        const auto t = extensions.find("KHR_texture_transform");
        if (t != extensions.end()) {
            const tinygltf::Value& v = t->second;
            auto pair = [&](const char* key, double fallback) {
                glm::dvec2 p(fallback);
                if (v.IsObject() && v.Has(key)) {
                    const tinygltf::Value& a = v.Get(key);
                    if (!a.IsArray() || a.ArrayLen() != 2 || !(a.Get(0).IsNumber() || a.Get(0).IsInt()) ||
                        !(a.Get(1).IsNumber() || a.Get(1).IsInt()))
                        fail(material + ": " + name + " KHR_texture_transform " + key + " is not 2 numbers");
                    p = glm::dvec2(a.Get(0).GetNumberAsDouble(), a.Get(1).GetNumberAsDouble());
                }
                return p;
            };
            const glm::dvec2 offset = pair("offset", 0.0), scale = pair("scale", 1.0);
            const double rotation = number(v, "rotation", 0.0);
            if (!std::isfinite(offset.x) || !std::isfinite(offset.y) || !std::isfinite(scale.x) || !std::isfinite(scale.y) ||
                !std::isfinite(rotation))
                fail(material + ": " + name + " KHR_texture_transform is not finite");
            const double c = std::cos(rotation), s = std::sin(rotation);
            // Column-major: u' = c sx u + s sy v + ox, v' = -s sx u + c sy v + oy.
            transform = glm::dmat3(c * scale.x, -s * scale.x, 0.0, s * scale.y, c * scale.y, 0.0, offset.x, offset.y, 1.0);
            if (v.IsObject() && v.Has("texCoord")) set = v.Get("texCoord").GetNumberAsInt();
            if (set < 0 || set > 255) fail(material + ": " + name + " KHR_texture_transform texCoord out of range");
        }
        if (uv.set < 0) {
            uv.set = set;
            uv.transform = transform;
            uv.slot = name;
        } else if (uv.set != set || uv.transform != transform) {
            warn(material + ": " + name + " asks for other texture coordinates than " + uv.slot + " (TEXCOORD_" +
                 std::to_string(set) + " or KHR_texture_transform); it is mapped with " + uv.slot + "'s");
        }
        return textureOf(index, material, scene);
    }

    // The scene texture of glTF texture `index` (one per image and sampler), or -1 with a warning
    // when its image could not be read.
    int textureOf(int index, const std::string& material, Scene& scene) {
        if (index >= int(m_.textures.size())) fail(material + ": texture " + std::to_string(index) + " does not exist");
        const tinygltf::Texture& t = m_.textures[size_t(index)];
        const std::pair<int, int> key(t.source, t.sampler);
        if (auto seen = textures_.find(key); seen != textures_.end()) return seen->second;
        int& made = textures_[key] = -1;
        if (t.source < 0 || t.source >= int(m_.images.size())) {
            warn(material + ": texture " + std::to_string(index) + " has no image gpurt reads (PNG, JPEG, BMP or TGA); the material keeps its colour");
            return -1;
        }
        const tinygltf::Image& stored = m_.images[size_t(t.source)];
        if (stored.bufferView >= 0 && !images_.images.count(t.source) && !images_.errors.count(t.source)) {
            const std::string what = "image " + std::to_string(t.source);
            if (stored.bufferView >= int(m_.bufferViews.size())) fail(what + ": buffer view " + std::to_string(stored.bufferView) + " does not exist");
            const tinygltf::BufferView& view = m_.bufferViews[size_t(stored.bufferView)];
            if (view.buffer < 0 || view.buffer >= int(m_.buffers.size())) fail(what + ": buffer " + std::to_string(view.buffer) + " does not exist");
            const std::vector<unsigned char>& data = m_.buffers[size_t(view.buffer)].data;
            if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
                fail(what + ": buffer view " + std::to_string(stored.bufferView) + " (" + std::to_string(view.byteLength) +
                     " bytes at " + std::to_string(view.byteOffset) + ") runs past its buffer of " + std::to_string(data.size()) + " bytes");
            try {
                images_.images[t.source] = decodeImage(data.data() + view.byteOffset, view.byteLength, what);
            } catch (const InputError& e) {
                images_.errors[t.source] = e.what();
            }
        }
        const auto image = images_.images.find(t.source);
        if (image == images_.images.end()) {
            const auto error = images_.errors.find(t.source);
            const tinygltf::Image& source = m_.images[size_t(t.source)];
            warn(material + ": " +
                 (error != images_.errors.end() ? error->second
                                                : "image " + std::to_string(t.source) + (source.uri.empty() ? "" : " ('" + source.uri + "')") +
                                                      " could not be read") +
                 "; the material keeps its colour");
            return -1;
        }
        Texture texture;
        const tinygltf::Image& source = m_.images[size_t(t.source)];
        texture.name = source.uri.empty() || source.uri.compare(0, 5, "data:") == 0 ? name_ + " image " + std::to_string(t.source) : source.uri;
        texture.image = image->second;
        if (t.sampler >= 0) {
            if (t.sampler >= int(m_.samplers.size())) fail("texture " + std::to_string(index) + ": sampler " + std::to_string(t.sampler) + " does not exist");
            const tinygltf::Sampler& sampler = m_.samplers[size_t(t.sampler)];
            texture.wrapS = wrapOf(sampler.wrapS);
            texture.wrapT = wrapOf(sampler.wrapT);
        }
        scene.textures.push_back(std::move(texture));
        return made = int(scene.textures.size() - 1);
    }

    static uint32_t wrapOf(int mode) {
        if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return kWrapClamp;
        if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return kWrapMirror;
        return kWrapRepeat;
    }

    void camera(int index, const glm::dmat4& world, const std::string& at, Scene& scene) {
        if (index >= int(m_.cameras.size())) fail(at + ": camera " + std::to_string(index) + " does not exist");
        const tinygltf::Camera& c = m_.cameras[size_t(index)];
        if (scene.camera || c.type != "perspective") return;  // the first perspective camera
        const double yfov = c.perspective.yfov * 180.0 / 3.14159265358979323846;
        if (!(yfov > 0.0 && yfov < 180.0)) fail("camera " + std::to_string(index) + ": yfov outside (0, pi)");
        const glm::dvec3 eye(world * glm::dvec4(0, 0, 0, 1));
        const glm::dvec3 forward(world * glm::dvec4(0, 0, -1, 0));
        const glm::dvec3 up(world * glm::dvec4(0, 1, 0, 0));
        const double length = glm::length(forward);
        if (!(length > 0.0) || !std::isfinite(length) || glm::length(glm::cross(forward, up)) == 0.0)
            fail(at + ": camera " + std::to_string(index) + " has no view direction (a degenerate transform)");
        CameraSpec spec;
        spec.eye = glm::vec3(eye);
        spec.target = glm::vec3(eye + forward / length);
        spec.up = glm::vec3(up);
        spec.fovy = float(yfov);
        scene.camera = spec;
    }

    // A KHR_lights_punctual light at the node (it shines down the node's -z), in gpurt's units: the
    // glTF Sample Viewer's, pi times gpurt's own (Scene.h Light), so the intensity is divided by pi.
    void punctualLight(const tinygltf::Value& which, const glm::dmat4& world, const std::string& at, Scene& scene) {
        const int index = which.IsInt() || which.IsNumber() ? which.GetNumberAsInt() : -1;
        if (index < 0 || index >= int(m_.lights.size())) fail(at + ": light " + std::to_string(index) + " does not exist");
        const tinygltf::Light& l = m_.lights[size_t(index)];
        const std::string name = "light " + std::to_string(index);
        Light light;
        if (l.type == "point") light.kind = LightKind::Point;
        else if (l.type == "spot") light.kind = LightKind::Spot;
        else if (l.type == "directional") light.kind = LightKind::Directional;
        else {
            warn(name + ": a light of type '" + l.type + "' is not used");
            return;
        }
        light.position = glm::vec3(world * glm::dvec4(0, 0, 0, 1));
        const glm::dvec3 down = glm::dvec3(world * glm::dvec4(0, 0, -1, 0));
        light.direction = glm::vec3(down / glm::length(down));
        if (l.color.size() == 3) light.color = glm::vec3(float(l.color[0]), float(l.color[1]), float(l.color[2]));
        light.intensity = float(l.intensity / std::numbers::pi);
        if (!finite(light.position) || !finite(light.color) || !std::isfinite(light.intensity) || light.intensity < 0.0f ||
            glm::any(glm::lessThan(light.color, glm::vec3(0.0f))))
            fail(name + ": colour and intensity must be finite and >= 0");
        if (light.kind != LightKind::Point && !finite(light.direction))
            fail(at + ": the node's transform gives " + name + " no direction");
        if (light.kind == LightKind::Spot) {
            const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
            if (!(inner >= 0.0 && inner < outer && outer <= std::numbers::pi / 2.0))
                fail(name + ": the spot's cone angles must be 0 <= innerConeAngle < outerConeAngle <= pi / 2");
            light.innerCone = float(inner);
            light.outerCone = float(outer);
        }
        if (l.range != 0.0) {
            if (light.kind == LightKind::Directional) warn(name + ": a directional light's range is not used (the specification ignores it)");
            else if (!(l.range > 0.0 && std::isfinite(l.range))) fail(name + ": range must be > 0");
            // The range is in the light's node units: scaled as its transform scales lengths.
            else light.range = float(l.range * std::cbrt(std::abs(glm::determinant(glm::dmat3(world)))));
        }
        scene.lights.push_back(light);
    }

    const tinygltf::Model& m_;
    std::string name_;
    std::vector<int> materialIds_;
    std::vector<MaterialUv> uvs_;  // per scene material: the texture coordinates of its textures
    std::map<std::pair<int, float>, int> roughnessFromGloss_;  // readGlossiness's textures, by source and factor
    std::map<std::pair<int, int>, int> textures_;  // (image, sampler) -> scene texture | -1
    DecodedImages& images_;
    std::set<int> onPath_;
    mutable DracoPrimitive draco_;                  // the last primitive decoded (dracoOf)
    std::map<int, std::vector<glm::dmat4>> skins_;  // skin -> its joint matrices
    std::vector<int> parents_;                      // node -> its parent, or -1 (worldOf)
    std::set<std::string> warned_;                  // warnOnce's keys
    struct LeftOut {
        size_t count = 0;
        std::string first;
    };
    std::map<int, LeftOut> leftOut_;  // mode -> the primitives of points and lines left out
};

}  // namespace

bool looksLikeGlb(const std::string& head) { return head.compare(0, 4, "glTF") == 0; }

Scene parseGltf(const std::string& bytes, const std::string& name, const std::filesystem::path& folder) {
    const FileLoc file{name};
    if (bytes.size() > UINT32_MAX) failAt(file, "larger than a glTF file can be (4 GiB)");
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    DecodedImages images;
    images.name = name;
    loader.SetImageLoader(decodeGltfImage, &images);
    std::string err, warn;
    const bool glb = looksLikeGlb(bytes);
    const std::string readable = withoutDracoIndices(withMeshoptDecoded(bytes, name, folder));
    if (readable.size() > UINT32_MAX) failAt(file, "larger than a glTF file can be (4 GiB)");
    // Known by its content, whatever its name says (CONTRACT.md; Blender's importer does the same).
    const std::string extension = lowerExtension(name);
    if (!glb && extension == ".glb") warnAt(file, "named .glb but a JSON glTF file (not binary): read as JSON glTF");
    if (glb && extension == ".gltf") warnAt(file, "named .gltf but a binary glTF file (.glb): read as binary glTF");
    bool ok = false;
    try {
        ok = glb ? loader.LoadBinaryFromMemory(
                       &model, &err, &warn, reinterpret_cast<const unsigned char*>(readable.data()),
                       unsigned(readable.size()), folder.string())
                 : loader.LoadASCIIFromString(&model, &err, &warn, readable.data(),
                                              unsigned(readable.size()), folder.string());
    } catch (const std::exception& e) {
        failAt(file, std::string("not a glTF file (") + e.what() + ")");
    }
    if (!ok) failAt(file, err.empty() ? std::string("not a glTF file") : firstLine(err));
    std::istringstream warnings(warn);
    for (std::string line; std::getline(warnings, line);)
        if (!line.empty()) warnAt(file, line);
    return GltfReader(model, name, images).read();
}

Scene loadGltf(const std::filesystem::path& path) {
    return parseGltf(readSceneFile(path), path.string(), path.parent_path());
}

}  // namespace gpurt
