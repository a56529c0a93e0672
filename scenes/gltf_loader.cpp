// glTF 2.0 import (see gltf_loader.h): the container, JSON, schema and resources are checked by
// the stages in glb_container.h, gltf_schema.h and gltf_resources.h; then tinygltf builds its
// model from the checked document, with every URI served from bytes already read, and this
// module validates every accessor it touches, flattens the scene's node tree into world-space
// triangle lists with their base colour materials and sRGB-decoded textures, and picks the
// file's camera. Any defect is a SceneError.

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "scenes/glb_container.h"
#include "scenes/gltf_loader.h"
#include "scenes/gltf_messages.h"
#include "scenes/gltf_resources.h"
#include "scenes/gltf_schema.h"
#include "scenes/scene.h"
#include "scenes/texture.h"

namespace scenes {
namespace {

// glTF buffers are little-endian; accessors are read with memcpy straight into host types.
static_assert(std::endian::native == std::endian::little, "the glTF reader assumes little-endian");

// A node DAG may reference the same subtree many times; this stops exponential blow-up.
constexpr std::size_t kMaxNodeInstances = 1u << 20;
// An accessor without a bufferView costs no file bytes, so its count alone must be bounded.
constexpr std::size_t kMaxBufferlessElements = 1u << 24;

// Extensions that only change appearance leave positions and indices readable as plain glTF.
constexpr std::array<std::string_view, 5> kAppearancePrefixes = {
    "KHR_materials_", "KHR_texture_", "EXT_texture_", "KHR_lights_", "KHR_technique"};

constexpr std::string_view kDracoExtension = "KHR_draco_mesh_compression";
constexpr std::string_view kDracoUnsupported =
    "requires KHR_draco_mesh_compression (Draco-compressed meshes), which aasim does not "
    "support; re-export the file without Draco compression";

struct SkippedKind {
  std::string_view name;
  std::size_t count = 0;
};

std::string Lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// tinygltf reports several problems separated by newlines; our messages are one line each.
std::string OneLine(const std::string& text) {
  std::string joined;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (!joined.empty()) joined += "; ";
    joined += line;
  }
  return gltf::Excerpt(joined, 4 * gltf::kExcerptBytes);
}

void PrintWarnings(gltf::WarningLog& warnings, const std::string& text) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    warnings.Warn(gltf::Excerpt(line, 4 * gltf::kExcerptBytes));
  }
}

std::string FormatVec3(const glm::vec3& v) {
  std::ostringstream text;
  text << '(' << v.x << ", " << v.y << ", " << v.z << ')';
  return text.str();
}

std::string ComponentTypeName(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "byte";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "unsigned byte";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "short";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "unsigned short";
    case TINYGLTF_COMPONENT_TYPE_INT: return "int";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "unsigned int";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "float";
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return "double";
    default: return "component type " + std::to_string(componentType);
  }
}

std::string TypeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "unknown type " + std::to_string(type);
  }
}

// Labels are built with append: GCC 12 warns falsely (-Wrestrict) on "literal" + temporary.
std::string MeshLabel(const tinygltf::Mesh& mesh, int index) {
  std::string label = "mesh ";
  if (mesh.name.empty()) return label.append(std::to_string(index));
  return label.append(gltf::Quoted(mesh.name));
}

bool IsFinite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string FormatNumber(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// False for non-finite coordinates too.
bool WithinCoordinateBound(const glm::dvec3& p) {
  return std::abs(p.x) <= kMaxGltfCoordinate && std::abs(p.y) <= kMaxGltfCoordinate &&
         std::abs(p.z) <= kMaxGltfCoordinate;
}

std::string CoordinateBoundText() {
  return "outside the +-" + FormatNumber(kMaxGltfCoordinate) +
         " aasim accepts for world coordinates (docs/scenes.md)";
}

bool IsAppearanceExtension(const std::string& name) {
  return std::any_of(kAppearancePrefixes.begin(), kAppearancePrefixes.end(),
                     [&](std::string_view prefix) { return name.starts_with(prefix); });
}

// Only base colour images are ever drawn, so decoding waits until a material needs one: here
// the encoded bytes of a uri image (served by Serve, `size` bytes) are kept as they
// are. A bufferView image is left alone: the flattener reads it through its own checks.
bool KeepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView >= 0 || size <= 0) return true;
  image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

// Decoding failures of images that claim to be PNG or JPEG are errors; other formats (KTX2,
// WebP, ...) are dropped with a warning.
bool IsPngOrJpeg(std::span<const unsigned char> bytes, const gltf::ImageOrigin& origin) {
  if (SniffImageFormat(bytes) != ImageFormat::Other) return true;
  if (origin.mediaType == "image/png" || origin.mediaType == "image/jpeg") return true;
  const std::string extension = Lowercase(std::filesystem::path(origin.uri).extension().string());
  return extension == ".png" || extension == ".jpg" || extension == ".jpeg";
}

// One warning per extension the file uses: each says what aasim draws instead.
std::string IgnoredExtensionMessage(const std::string& name) {
  std::string text = "extension " + gltf::Excerpt(name) + " is ignored";
  if (name == "KHR_texture_transform") return text + ": texture coordinates are used untransformed";
  if (name == "KHR_lights_punctual") {
    return text + ": aasim lights every scene with its own directional light";
  }
  if (name == "KHR_materials_pbrSpecularGlossiness") {
    return text + ": the pbrMetallicRoughness base colour is used";
  }
  if (name.starts_with("KHR_materials_")) {
    return text + ": aasim shades the base colour with Lambert only";
  }
  if (name == "KHR_texture_basisu" || name == "EXT_texture_webp") {
    return text + ": textures fall back to their PNG or JPEG source, if they have one";
  }
  if (name == kDracoExtension) return text + ": the uncompressed fallback geometry is used";
  return text;
}

// Where an accessor's elements live: `data` is null for an accessor without a bufferView,
// whose elements are all zero by the glTF spec.
struct ElementView {
  const unsigned char* data = nullptr;
  std::size_t stride = 0;
  std::size_t count = 0;
};

// The element kinds this loader reads, with the names used in messages.
struct AccessorUse {
  std::string_view role;  // "POSITION", "NORMAL", "TEXCOORD_0", "indices"
  int type;               // TINYGLTF_TYPE_*
};

// A camera reached through the node tree, with that node instance's world transform.
struct CameraInstance {
  int camera;
  int node;
  glm::dmat4 world;
};

// Works on a model whose document passed ValidateGltfSchema: every index it follows exists, every
// array has its schema length, every number its schema range; the checks here are those the
// schema cannot express.
class GltfFlattener {
 public:
  GltfFlattener(const std::string& file, const tinygltf::Model& model,
                const std::vector<gltf::ImageOrigin>& imageOrigins, gltf::WarningLog& warnings)
      : file_(file), model_(model), imageOrigins_(imageOrigins), warnings_(warnings) {}

  // Everything but the scene's name.
  Scene Flatten(float aspect) {
    WarnUnmodelledFileFeatures();
    for (int root : RootNodes()) WalkFrom(root);
    WarnSkipped();
    if (meshes_.empty()) {
      Fail("contains no triangles to draw (" + std::to_string(meshInstances_) +
           " mesh instances in the scene)");
    }
    Scene scene;
    scene.meshes = std::move(meshes_);
    scene.materials = std::move(materials_);
    scene.textures = std::move(textures_);
    scene.bounds = ComputeBounds(scene.meshes);
    scene.camera = MakeCamera(scene.bounds, aspect);
    return scene;
  }

 private:
  struct PathEntry {
    int node;
    glm::dmat4 world;
    std::size_t nextChild;
  };

  [[noreturn]] void Fail(const std::string& problem) const {
    throw SceneError(file_ + ": " + problem);
  }

  // Each distinct text is printed once per file, however many elements it concerns.
  void Warn(const std::string& text) { warnings_.Warn(text); }

  void WarnUnmodelledFileFeatures() {
    for (const std::string& name : model_.extensionsUsed) Warn(IgnoredExtensionMessage(name));
    for (const std::string& name : model_.extensionsRequired) Warn(IgnoredExtensionMessage(name));
    if (!model_.animations.empty()) {
      Warn(std::to_string(model_.animations.size()) +
           " animation(s) ignored: the scene is drawn in its static pose");
    }
    if (!model_.skins.empty()) {
      Warn("skins are ignored: skinned meshes are drawn in their bind pose");
    }
  }

  std::vector<int> RootNodes() const {
    if (model_.defaultScene >= 0) {
      return model_.scenes.at(static_cast<std::size_t>(model_.defaultScene)).nodes;
    }
    if (!model_.scenes.empty()) return model_.scenes.front().nodes;
    return ParentlessNodes();
  }

  // Without a scene, glTF leaves the roots implicit: every node that is nobody's child.
  std::vector<int> ParentlessNodes() const {
    std::vector<bool> isChild(model_.nodes.size(), false);
    for (const tinygltf::Node& node : model_.nodes) {
      for (int child : node.children) isChild.at(static_cast<std::size_t>(child)) = true;
    }
    std::vector<int> roots;
    for (std::size_t i = 0; i < isChild.size(); ++i) {
      if (!isChild[i]) roots.push_back(static_cast<int>(i));
    }
    return roots;
  }

  // Iterative depth-first walk: deep node chains must not exhaust the call stack.
  void WalkFrom(int root) {
    std::vector<PathEntry> path;
    std::vector<bool> onPath(model_.nodes.size(), false);
    Enter(root, glm::dmat4(1.0), path, onPath);
    while (!path.empty()) {
      PathEntry& top = path.back();
      const std::vector<int>& children = Node(top.node).children;
      if (top.nextChild < children.size()) {
        const int child = children[top.nextChild++];
        const glm::dmat4 parentWorld = top.world;
        Enter(child, parentWorld, path, onPath);
      } else {
        onPath[static_cast<std::size_t>(top.node)] = false;
        path.pop_back();
      }
    }
  }

  void Enter(int nodeIndex, const glm::dmat4& parentWorld, std::vector<PathEntry>& path,
             std::vector<bool>& onPath) {
    const tinygltf::Node& node = Node(nodeIndex);
    if (onPath[static_cast<std::size_t>(nodeIndex)]) FailRecursion(nodeIndex, path);
    if (++nodeInstances_ > kMaxNodeInstances) {
      Fail("node graph expands to more than " + std::to_string(kMaxNodeInstances) +
           " node instances");
    }
    const glm::dmat4 world = parentWorld * LocalTransform(node);
    if (node.mesh >= 0) AddMeshInstance(node.mesh, world);
    if (node.camera >= 0) NoteCamera(node.camera, nodeIndex, world);
    onPath[static_cast<std::size_t>(nodeIndex)] = true;
    path.push_back(PathEntry{nodeIndex, world, 0});
  }

  [[noreturn]] void FailRecursion(int nodeIndex, const std::vector<PathEntry>& path) const {
    std::string cycle;
    for (const PathEntry& entry : path) cycle += std::to_string(entry.node) + " -> ";
    Fail("node " + std::to_string(nodeIndex) + " is its own ancestor (recursive node graph " +
         cycle + std::to_string(nodeIndex) + ")");
  }

  const tinygltf::Node& Node(int index) const {
    return model_.nodes.at(static_cast<std::size_t>(index));
  }

  // The schema bounds every value, so the local transform is finite; world transforms may still
  // overflow down a long chain, which the position and camera checks catch.
  static glm::dmat4 LocalTransform(const tinygltf::Node& node) {
    if (!node.matrix.empty()) return glm::make_mat4(node.matrix.data());  // both column-major
    glm::dmat4 local(1.0);
    if (!node.translation.empty()) {
      local = glm::translate(local, glm::make_vec3(node.translation.data()));
    }
    if (!node.rotation.empty()) {
      const std::vector<double>& r = node.rotation;  // glTF order: x, y, z, w
      const glm::dquat rotation(r[3], r[0], r[1], r[2]);
      // Exporters write unit quaternions rounded to float; renormalising removes the tiny
      // scale that rounding would otherwise add (the schema check bounds it).
      local *= glm::mat4_cast(rotation / glm::length(rotation));
    }
    if (!node.scale.empty()) local = glm::scale(local, glm::make_vec3(node.scale.data()));
    return local;
  }

  void AddMeshInstance(int meshIndex, const glm::dmat4& world) {
    ++meshInstances_;
    const tinygltf::Mesh& mesh = model_.meshes.at(static_cast<std::size_t>(meshIndex));
    const std::string label = MeshLabel(mesh, meshIndex);
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      const std::string where = label + " primitive " + std::to_string(p);
      std::string name = mesh.name.empty() ? label : mesh.name;
      if (mesh.primitives.size() > 1) name.append("#").append(std::to_string(p));
      AddPrimitive(mesh.primitives[p], where, std::move(name), world);
    }
  }

  // Returns false (after counting it) for point and line primitives, which have no coverage
  // area and so are skipped.
  bool IsTriangleMode(int mode, const std::string& where) {
    switch (mode) {
      case TINYGLTF_MODE_TRIANGLES:
      case TINYGLTF_MODE_TRIANGLE_STRIP:
      case TINYGLTF_MODE_TRIANGLE_FAN: return true;
      case TINYGLTF_MODE_POINTS:
      case TINYGLTF_MODE_LINE:
      case TINYGLTF_MODE_LINE_LOOP:
      case TINYGLTF_MODE_LINE_STRIP: ++skipped_[static_cast<std::size_t>(mode)].count; return false;
      default: Fail(where + ": unknown primitive mode " + std::to_string(mode));
    }
  }

  void AddPrimitive(const tinygltf::Primitive& primitive, const std::string& where,
                    std::string name, const glm::dmat4& world) {
    if (!IsTriangleMode(primitive.mode, where)) return;
    const auto positionIt = primitive.attributes.find("POSITION");
    if (positionIt == primitive.attributes.end()) Fail(where + ": has no POSITION attribute");
    ReserveSceneSize(primitive, positionIt->second, where);
    Mesh mesh;
    mesh.name = std::move(name);
    mesh.positions = ReadVec3(positionIt->second, {"POSITION", TINYGLTF_TYPE_VEC3}, where);
    CheckFinite(mesh.positions, "position", where);
    const auto normalIt = primitive.attributes.find("NORMAL");
    if (normalIt != primitive.attributes.end()) {
      mesh.normals = ReadVec3(normalIt->second, {"NORMAL", TINYGLTF_TYPE_VEC3}, where);
      CheckFinite(mesh.normals, "normal", where);
    }
    const auto texcoordIt = primitive.attributes.find("TEXCOORD_0");
    if (texcoordIt != primitive.attributes.end()) {
      mesh.texcoords = ReadTexcoords(texcoordIt->second, where);
    }
    mesh.material = SceneMaterial(primitive.material, !mesh.texcoords.empty());
    if (!primitive.targets.empty()) {
      Warn("morph targets are ignored: meshes are drawn in their base shape");
    }
    if (primitive.attributes.contains("COLOR_0")) Warn("vertex colours (COLOR_0) are ignored");
    const bool indexed = primitive.indices >= 0;
    std::vector<std::uint32_t> vertexOrder = indexed ? ReadIndices(primitive.indices, where)
                                                     : SequentialIndices(mesh.positions.size());
    if (indexed) CheckIndexRange(vertexOrder, mesh.positions.size(), where);
    mesh.indices = ToTriangleList(primitive.mode, vertexOrder, indexed, where);
    if (mesh.indices.empty()) return;
    TransformToWorld(mesh, world, where);
    meshes_.push_back(std::move(mesh));
  }

  // Checked before anything of the primitive is read, as instancing may repeat one mesh
  // kMaxNodeInstances times: the attributes agree in count, and the scene stays within its
  // vertex and index budget.
  void ReserveSceneSize(const tinygltf::Primitive& primitive, int position,
                        const std::string& where) {
    const std::size_t vertices = Accessor(position).count;
    for (const auto& [role, noun] : {std::pair{"NORMAL", "normals"},
                                     std::pair{"TEXCOORD_0", "texture coordinates"}}) {
      const auto it = primitive.attributes.find(role);
      if (it != primitive.attributes.end() && Accessor(it->second).count != vertices) {
        Fail(where + ": " + std::to_string(Accessor(it->second).count) + " " + noun + " for " +
             std::to_string(vertices) + " positions");
      }
    }
    const std::size_t listed =
        primitive.indices >= 0 ? Accessor(primitive.indices).count : vertices;
    sceneVertices_ += vertices;
    sceneIndices_ += primitive.mode == TINYGLTF_MODE_TRIANGLES ? listed : 3 * listed;
    if (sceneVertices_ > kMaxGltfSceneVertices || sceneIndices_ > kMaxGltfSceneIndices) {
      Fail(where + ": with its " + std::to_string(vertices) + " vertices and " +
           std::to_string(listed) + " indices the scene's mesh instances exceed " +
           std::to_string(kMaxGltfSceneVertices) + " vertices or " +
           std::to_string(kMaxGltfSceneIndices) + " triangle-list indices, the most aasim loads");
    }
  }

  // --- Materials and textures -----------------------------------------------------------------

  // The Scene::materials index for a primitive's glTF material (-1 stays -1). A textured
  // material on a primitive without TEXCOORD_0 becomes an untextured copy: there is nothing to
  // sample the texture with.
  int SceneMaterial(int index, bool hasTexcoords) {
    if (index < 0) return -1;
    const auto [it, inserted] = materialIndex_.try_emplace(index, -1);
    if (inserted) it->second = AddMaterial(index);
    const int converted = it->second;
    if (hasTexcoords || materials_[static_cast<std::size_t>(converted)].baseColourTexture < 0) {
      return converted;
    }
    Warn("primitives without TEXCOORD_0 are drawn with their material's base colour factor only "
         "(their base colour texture has no coordinates)");
    const auto [variant, added] = untexturedVariant_.try_emplace(converted, -1);
    if (added) {
      Material untextured = materials_[static_cast<std::size_t>(converted)];
      untextured.name.append(" (untextured)");
      untextured.baseColourTexture = -1;
      materials_.push_back(std::move(untextured));
      variant->second = static_cast<int>(materials_.size()) - 1;
    }
    return variant->second;
  }

  int AddMaterial(int index) {
    const tinygltf::Material& source = model_.materials.at(static_cast<std::size_t>(index));
    const std::vector<double>& factor = source.pbrMetallicRoughness.baseColorFactor;
    WarnUnmodelledMaps(source);
    Material material;
    material.name = source.name.empty() ? "material " + std::to_string(index) : source.name;
    material.baseColourFactor = glm::vec4(glm::dvec4(factor.at(0), factor.at(1), factor.at(2),
                                                     factor.at(3)));
    material.baseColourTexture = BaseColourTexture(source.pbrMetallicRoughness.baseColorTexture);
    materials_.push_back(std::move(material));
    return static_cast<int>(materials_.size()) - 1;
  }

  void WarnUnmodelledMaps(const tinygltf::Material& source) {
    if (source.normalTexture.index >= 0) {
      Warn("normal maps are ignored: shading uses the vertex normals");
    }
    if (source.occlusionTexture.index >= 0) Warn("occlusion maps are ignored");
    if (source.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0) {
      Warn("metallic-roughness maps are ignored: shading is Lambert on the base colour");
    }
    const bool emissive = std::any_of(source.emissiveFactor.begin(), source.emissiveFactor.end(),
                                      [](double v) { return v != 0.0; });
    if (emissive || source.emissiveTexture.index >= 0) Warn("emission is ignored");
    if (source.alphaMode != "OPAQUE") {
      Warn("alphaMode " + source.alphaMode + " is ignored: every surface is drawn opaque");
    }
  }

  int BaseColourTexture(const tinygltf::TextureInfo& info) {
    if (info.index < 0) return -1;
    if (info.texCoord != 0) {
      Warn("base colour textures on TEXCOORD_" + std::to_string(info.texCoord) +
           " are not supported (TEXCOORD_0 only): their materials use the base colour factor");
      return -1;
    }
    const tinygltf::Texture& texture = model_.textures.at(static_cast<std::size_t>(info.index));
    WarnUnmodelledSampler(texture.sampler);
    if (texture.source < 0) {
      Warn("textures without a PNG or JPEG source image are dropped: their materials use the "
           "base colour factor");
      return -1;
    }
    // Textures differ from their image only by the sampler, which aasim does not model.
    const auto [it, inserted] = imageTexture_.try_emplace(texture.source, -1);
    if (inserted) {
      std::optional<Texture> decoded = TextureFromImage(texture.source);
      if (decoded) {
        textures_.push_back(std::move(*decoded));
        it->second = static_cast<int>(textures_.size()) - 1;
      }
    }
    return it->second;
  }

  void WarnUnmodelledSampler(int index) {
    if (index < 0) return;
    const tinygltf::Sampler& sampler = model_.samplers.at(static_cast<std::size_t>(index));
    if (sampler.wrapS != TINYGLTF_TEXTURE_WRAP_REPEAT ||
        sampler.wrapT != TINYGLTF_TEXTURE_WRAP_REPEAT) {
      Warn("texture wrap modes other than REPEAT are sampled as REPEAT");
    }
    const std::array<int, 3> nearest = {TINYGLTF_TEXTURE_FILTER_NEAREST,
                                        TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST,
                                        TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR};
    if (std::find(nearest.begin(), nearest.end(), sampler.magFilter) != nearest.end() ||
        std::find(nearest.begin(), nearest.end(), sampler.minFilter) != nearest.end()) {
      Warn("NEAREST texture filters are sampled bilinearly");
    }
  }

  // nullopt (with a warning) for an image that is not PNG or JPEG; a PNG or JPEG that fails to
  // decode, or is too large, is an error.
  std::optional<Texture> TextureFromImage(int index) {
    const tinygltf::Image& image = model_.images.at(static_cast<std::size_t>(index));
    const gltf::ImageOrigin& origin = imageOrigins_.at(static_cast<std::size_t>(index));
    std::string name = !image.name.empty() ? image.name
                       : !origin.uri.empty() ? origin.uri
                                             : "image " + std::to_string(index);
    std::string where = "image " + std::to_string(index);
    if (!image.name.empty() || !origin.uri.empty()) where.append(" ").append(gltf::Quoted(name));
    const std::span<const unsigned char> encoded = EncodedImage(image, where);
    if (!IsPngOrJpeg(encoded, origin)) {
      Warn("images that are not PNG or JPEG are dropped (first: " + where +
           "): their materials use the base colour factor");
      return std::nullopt;
    }
    const std::string prefix = file_ + ": " + where;
    const ImageSize size = ReadImageSize(encoded, prefix);
    sceneTexels_ += static_cast<std::size_t>(size.width) * static_cast<std::size_t>(size.height);
    if (sceneTexels_ > kMaxGltfSceneTexels) {
      Fail(where + ": its " + std::to_string(size.width) + "x" + std::to_string(size.height) +
           " texels bring the scene's textures past the " + std::to_string(kMaxGltfSceneTexels) +
           " texels aasim decodes per scene");
    }
    Texture texture = DecodeImage(encoded, prefix, ColourEncoding::Srgb);
    texture.name = std::move(name);
    return texture;
  }

  std::span<const unsigned char> EncodedImage(const tinygltf::Image& image,
                                              const std::string& where) const {
    if (image.bufferView < 0) return image.image;
    const tinygltf::BufferView& view =
        model_.bufferViews.at(static_cast<std::size_t>(image.bufferView));
    return {BufferViewData(view, image.bufferView, where), view.byteLength};
  }

  // --- Camera -----------------------------------------------------------------------------------

  // The schema allows the two types only.
  void NoteCamera(int cameraIndex, int nodeIndex, const glm::dmat4& world) {
    const bool perspective =
        model_.cameras.at(static_cast<std::size_t>(cameraIndex)).type == "perspective";
    std::optional<CameraInstance>& first = perspective ? perspective_ : orthographic_;
    if (!first) first = CameraInstance{cameraIndex, nodeIndex, world};
  }

  Camera MakeCamera(const Bounds& bounds, float aspect) {
    if (perspective_) return FileCamera(*perspective_, bounds, aspect);
    if (orthographic_) {
      Warn("orthographic camera " + std::to_string(orthographic_->camera) +
           " is not supported (aasim renders perspective views): framing the scene bounds instead");
    }
    return FrameBounds(bounds, aspect);
  }

  // The schema check has made yfov, znear and zfar valid as floats (absent zfar reads 0).
  Camera FileCamera(const CameraInstance& instance, const Bounds& bounds, float aspect) {
    const tinygltf::Camera& source = model_.cameras.at(static_cast<std::size_t>(instance.camera));
    const tinygltf::PerspectiveCamera& lens = source.perspective;
    std::string where = "camera " + std::to_string(instance.camera);
    if (!source.name.empty()) where.append(" ").append(gltf::Quoted(source.name));
    const bool infinite = lens.zfar == 0.0;
    // glTF cameras look down their node's -z with +y up.
    const glm::dvec3 eye(instance.world[3]);
    if (!WithinCoordinateBound(eye)) {
      Fail("node " + std::to_string(instance.node) + " (" + where + "): the eye lies at " +
           FormatVec3(glm::vec3(eye)) + " after its node transforms, " + CoordinateBoundText());
    }
    const glm::dvec3 back(instance.world[2]);
    const glm::dvec3 right = glm::cross(-back, glm::dvec3(instance.world[1]));
    if (!(glm::length(back) > 0.0) || !(glm::length(right) > 0.0)) {
      Fail("node " + std::to_string(instance.node) + " (" + where +
           ") has a degenerate transform: no view direction or up vector");
    }
    const glm::dvec3 forward = -glm::normalize(back);
    const glm::dvec3 centre(bounds.Centre());
    // The target only anchors orbits and dollies (motion.h): put it at the scene's depth.
    const double depth = glm::dot(centre - eye, forward);
    const double focus =
        depth > lens.znear ? depth : std::max(glm::length(centre - eye), 2.0 * lens.znear);
    Camera camera;
    camera.eye = glm::vec3(eye);
    camera.target = glm::vec3(eye + forward * focus);
    camera.up = glm::vec3(glm::normalize(glm::cross(right, forward)));
    camera.verticalFovRadians = static_cast<float>(lens.yfov);
    camera.zNear = static_cast<float>(lens.znear);
    camera.zFar = static_cast<float>(lens.zfar);
    if (infinite) {
      double farthest = 0.0;
      for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p((corner & 1) ? bounds.max.x : bounds.min.x,
                           (corner & 2) ? bounds.max.y : bounds.min.y,
                           (corner & 4) ? bounds.max.z : bounds.min.z);
        farthest = std::max(farthest, glm::dot(p - eye, forward));
      }
      camera.zFar = static_cast<float>(std::max(farthest * 1.05, 2.0 * lens.znear));
      Warn(where + " has an infinite far plane; aasim uses zfar = " +
           FormatNumber(static_cast<double>(camera.zFar)) + ", just beyond the scene bounds");
    }
    // Planes far outside the scene only waste depth precision (2CylinderEngine's camera spans
    // 0.05 to 10^6 around a scene 750 units wide). Pulling them in to the bounding sphere, with
    // the slack EncloseBounds uses, clips nothing that the file's planes did not clip already.
    const double distance = glm::length(centre - eye);
    const double radius = 1.05 * static_cast<double>(bounds.Radius());
    const double tightNear = std::max(lens.znear, distance - radius);
    const double tightFar = std::min(static_cast<double>(camera.zFar), distance + radius);
    if (tightFar > tightNear) {
      camera.zNear = static_cast<float>(tightNear);
      camera.zFar = static_cast<float>(tightFar);
    }
    const auto imageAspect = static_cast<double>(aspect);
    if (lens.aspectRatio > 0.0 && std::abs(lens.aspectRatio - imageAspect) > 1e-3 * imageAspect) {
      Warn(where + ": aspectRatio " + FormatNumber(lens.aspectRatio) +
           " differs from the image's " + FormatNumber(imageAspect) +
           "; yfov is kept and the horizontal field of view follows the image");
    }
    return camera;
  }

  void CheckFinite(const std::vector<glm::vec3>& values, std::string_view what,
                   const std::string& where) const {
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (!IsFinite(values[i])) {
        Fail(where + ": vertex " + std::to_string(i) + " has a non-finite " + std::string(what) +
             " " + FormatVec3(values[i]));
      }
    }
  }

  void CheckIndexRange(const std::vector<std::uint32_t>& indices, std::size_t vertexCount,
                       const std::string& where) const {
    for (std::size_t i = 0; i < indices.size(); ++i) {
      if (indices[i] >= vertexCount) {
        Fail(where + ": index " + std::to_string(indices[i]) + " at position " +
             std::to_string(i) + " is out of range (" + std::to_string(vertexCount) +
             " vertices)");
      }
    }
  }

  static std::vector<std::uint32_t> SequentialIndices(std::size_t count) {
    std::vector<std::uint32_t> indices(count);
    std::iota(indices.begin(), indices.end(), 0u);
    return indices;
  }

  // Strips and fans use the glTF spec's vertex order, which keeps every triangle's winding.
  std::vector<std::uint32_t> ToTriangleList(int mode, const std::vector<std::uint32_t>& order,
                                            bool indexed, const std::string& where) const {
    const std::string noun = indexed ? " indices" : " vertices";
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      if (order.size() % 3 != 0) {
        Fail(where + ": triangle list has " + std::to_string(order.size()) + noun +
             ", not a multiple of 3");
      }
      return order;
    }
    if (order.size() < 3) {
      Fail(where + ": triangle " + (mode == TINYGLTF_MODE_TRIANGLE_STRIP ? "strip" : "fan") +
           " has " + std::to_string(order.size()) + noun + ", needs at least 3");
    }
    std::vector<std::uint32_t> list;
    list.reserve((order.size() - 2) * 3);
    for (std::size_t i = 0; i + 2 < order.size(); ++i) {
      if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        const std::size_t odd = i % 2;
        list.insert(list.end(), {order[i], order[i + 1 + odd], order[i + 2 - odd]});
      } else {
        list.insert(list.end(), {order[i + 1], order[i + 2], order[0]});
      }
    }
    return list;
  }

  void TransformToWorld(Mesh& mesh, const glm::dmat4& world, const std::string& where) const {
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      const glm::dvec3 p(world * glm::dvec4(glm::dvec3(mesh.positions[i]), 1.0));
      if (!WithinCoordinateBound(p)) {
        Fail(where + ": vertex " + std::to_string(i) + " lies at " + FormatVec3(glm::vec3(p)) +
             " after its node transforms, " + CoordinateBoundText());
      }
      mesh.positions[i] = glm::vec3(p);
    }
    const glm::dmat3 linear(world);
    const double determinant = glm::determinant(linear);
    // Cofactors are the inverse-transpose times the determinant; they stay defined when a
    // zero scale collapses the mesh, and the sign flip keeps normals pointing outwards.
    const glm::dmat3 normalMatrix =
        glm::dmat3(glm::cross(linear[1], linear[2]), glm::cross(linear[2], linear[0]),
                   glm::cross(linear[0], linear[1])) *
        (determinant < 0.0 ? -1.0 : 1.0);
    for (glm::vec3& normal : mesh.normals) {
      const glm::dvec3 n = normalMatrix * glm::dvec3(normal);
      const double length = glm::length(n);
      normal = length > 0.0 ? glm::vec3(n / length) : glm::vec3(0.0f);
    }
    // A mirroring transform turns counter-clockwise faces clockwise (glTF spec, "Meshes").
    if (determinant < 0.0) {
      for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
      }
    }
  }

  const tinygltf::Accessor& Accessor(int index) const {
    return model_.accessors.at(static_cast<std::size_t>(index));
  }

  // Checks the accessor's type and that all its elements lie inside its bufferView and buffer.
  ElementView ViewElements(int index, const AccessorUse& use, std::size_t elementSize,
                           const std::string& where) const {
    const tinygltf::Accessor& accessor = Accessor(index);
    const std::string name =
        where + ": " + std::string(use.role) + " accessor " + std::to_string(index);
    if (accessor.type != use.type) {
      Fail(name + " has type " + TypeName(accessor.type) + ", expected " + TypeName(use.type));
    }
    if (accessor.sparse.isSparse) Fail(name + " is sparse, which aasim does not support");
    ElementView view;
    view.count = accessor.count;
    if (accessor.bufferView < 0) {
      if (view.count > kMaxBufferlessElements) {
        Fail(name + " has no bufferView and " + std::to_string(view.count) +
             " elements, more than the " + std::to_string(kMaxBufferlessElements) + " allowed");
      }
      return view;
    }
    const tinygltf::BufferView& bufferView =
        model_.bufferViews.at(static_cast<std::size_t>(accessor.bufferView));
    const unsigned char* viewStart = BufferViewData(bufferView, accessor.bufferView, name);
    view.stride = bufferView.byteStride == 0 ? elementSize : bufferView.byteStride;
    if (view.stride < elementSize) {
      Fail(name + ": byteStride " + std::to_string(view.stride) + " is smaller than its " +
           std::to_string(elementSize) + "-byte elements");
    }
    if (!FitsInside(accessor.byteOffset, view.count, view.stride, elementSize,
                    bufferView.byteLength)) {
      Fail(name + " (" + std::to_string(view.count) + " elements at byte offset " +
           std::to_string(accessor.byteOffset) + ", stride " + std::to_string(view.stride) +
           ") reads past the end of bufferView " + std::to_string(accessor.bufferView) + " (" +
           std::to_string(bufferView.byteLength) + " bytes)");
    }
    view.data = viewStart + accessor.byteOffset;
    return view;
  }

  const unsigned char* BufferViewData(const tinygltf::BufferView& bufferView, int viewIndex,
                                      const std::string& name) const {
    const std::string viewName = name + ": bufferView " + std::to_string(viewIndex);
    // The schema check compared the view with the buffer's byteLength; this compares it with
    // the bytes tinygltf holds, as memory safety must not rest on the two agreeing.
    const std::vector<unsigned char>& data =
        model_.buffers.at(static_cast<std::size_t>(bufferView.buffer)).data;
    if (bufferView.byteOffset > data.size() ||
        bufferView.byteLength > data.size() - bufferView.byteOffset) {
      Fail(viewName + " (bytes " + std::to_string(bufferView.byteOffset) + " + " +
           std::to_string(bufferView.byteLength) + ") runs past the end of buffer " +
           std::to_string(bufferView.buffer) + " (" + std::to_string(data.size()) + " bytes)");
    }
    return data.data() + bufferView.byteOffset;
  }

  // Written to avoid overflow: counts and offsets come straight from the file.
  static bool FitsInside(std::size_t offset, std::size_t count, std::size_t stride,
                         std::size_t elementSize, std::size_t length) {
    if (count == 0) return offset <= length;
    if (offset > length || elementSize > length - offset) return false;
    return (count - 1) <= (length - offset - elementSize) / stride;
  }

  std::vector<glm::vec3> ReadVec3(int index, const AccessorUse& use,
                                  const std::string& where) const {
    const tinygltf::Accessor& accessor = Accessor(index);
    if (accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
      Fail(where + ": " + std::string(use.role) + " accessor " + std::to_string(index) + " holds " +
           ComponentTypeName(accessor.componentType) + " components; aasim reads float only");
    }
    const ElementView view = ViewElements(index, use, sizeof(float) * 3, where);
    std::vector<glm::vec3> values(view.count, glm::vec3(0.0f));
    if (view.data == nullptr) return values;
    for (std::size_t i = 0; i < view.count; ++i) {
      std::array<float, 3> xyz{};
      std::memcpy(xyz.data(), view.data + i * view.stride, sizeof(xyz));
      values[i] = glm::vec3(xyz[0], xyz[1], xyz[2]);
    }
    return values;
  }

  // Float, or unsigned byte or short normalized to [0, 1], as the glTF spec allows.
  std::vector<glm::vec2> ReadTexcoords(int index, const std::string& where) const {
    const AccessorUse use{"TEXCOORD_0", TINYGLTF_TYPE_VEC2};
    const tinygltf::Accessor& accessor = Accessor(index);
    const std::string name = where + ": TEXCOORD_0 accessor " + std::to_string(index);
    std::size_t size = 0;
    switch (accessor.componentType) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: size = 4; break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: size = 1; break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: size = 2; break;
      default:
        Fail(name + " holds " + ComponentTypeName(accessor.componentType) +
             " components; glTF allows float, or unsigned byte or short normalized");
    }
    if (size != 4 && !accessor.normalized) {
      Fail(name + " holds " + ComponentTypeName(accessor.componentType) +
           " components without \"normalized\": true, which glTF requires for them");
    }
    const ElementView view = ViewElements(index, use, 2 * size, where);
    std::vector<glm::vec2> values(view.count, glm::vec2(0.0f));
    if (view.data == nullptr) return values;
    const float maxValue = size == 1 ? 255.0f : 65535.0f;
    for (std::size_t i = 0; i < view.count; ++i) {
      const unsigned char* element = view.data + i * view.stride;
      if (size == 4) {
        std::array<float, 2> uv{};
        std::memcpy(uv.data(), element, sizeof(uv));
        values[i] = glm::vec2(uv[0], uv[1]);
      } else {
        values[i] = glm::vec2(static_cast<float>(ReadUnsigned(element, size)),
                              static_cast<float>(ReadUnsigned(element + size, size))) /
                    maxValue;
      }
      if (!std::isfinite(values[i].x) || !std::isfinite(values[i].y)) {
        Fail(where + ": vertex " + std::to_string(i) + " has a non-finite texture coordinate (" +
             FormatNumber(static_cast<double>(values[i].x)) + ", " +
             FormatNumber(static_cast<double>(values[i].y)) + ")");
      }
    }
    return values;
  }

  std::vector<std::uint32_t> ReadIndices(int index, const std::string& where) const {
    const AccessorUse use{"indices", TINYGLTF_TYPE_SCALAR};
    const tinygltf::Accessor& accessor = Accessor(index);
    std::size_t size = 0;
    switch (accessor.componentType) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: size = 1; break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: size = 2; break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: size = 4; break;
      default:
        Fail(where + ": indices accessor " + std::to_string(index) + " holds " +
             ComponentTypeName(accessor.componentType) +
             " components; glTF allows unsigned byte, short or int");
    }
    const ElementView view = ViewElements(index, use, size, where);
    std::vector<std::uint32_t> indices(view.count, 0u);
    if (view.data == nullptr) return indices;
    for (std::size_t i = 0; i < view.count; ++i) {
      indices[i] = ReadUnsigned(view.data + i * view.stride, size);
    }
    return indices;
  }

  static std::uint32_t ReadUnsigned(const unsigned char* bytes, std::size_t size) {
    if (size == 1) return bytes[0];
    if (size == 2) {
      std::uint16_t value = 0;
      std::memcpy(&value, bytes, sizeof(value));
      return value;
    }
    std::uint32_t value = 0;
    std::memcpy(&value, bytes, sizeof(value));
    return value;
  }

  void WarnSkipped() {
    for (const SkippedKind& kind : skipped_) {
      if (kind.count == 0) continue;
      Warn("skipped " + std::to_string(kind.count) + " " + std::string(kind.name) + " primitive" +
           (kind.count == 1 ? "" : "s") + " (only triangles have coverage)");
    }
  }

  const std::string& file_;
  const tinygltf::Model& model_;
  const std::vector<gltf::ImageOrigin>& imageOrigins_;
  gltf::WarningLog& warnings_;
  std::vector<Mesh> meshes_;
  std::vector<Material> materials_;
  std::vector<Texture> textures_;
  std::map<int, int> materialIndex_;      // glTF material -> materials_
  std::map<int, int> untexturedVariant_;  // materials_ entry -> its untextured copy
  std::map<int, int> imageTexture_;       // glTF image -> textures_, -1 when dropped
  std::optional<CameraInstance> perspective_;
  std::optional<CameraInstance> orthographic_;
  std::size_t nodeInstances_ = 0;
  std::size_t meshInstances_ = 0;
  std::size_t sceneVertices_ = 0;
  std::size_t sceneIndices_ = 0;
  std::size_t sceneTexels_ = 0;
  // Indexed by glTF mode; the triangle modes' slots stay unused.
  std::array<SkippedKind, 4> skipped_{SkippedKind{"POINTS"}, SkippedKind{"LINES"},
                                      SkippedKind{"LINE_LOOP"}, SkippedKind{"LINE_STRIP"}};
};

// Decided before the schema check, which would otherwise stop a Draco file at its first
// accessor without a bufferView instead of saying what the file needs.
void RequireSupportedExtensions(const nlohmann::json& document, const std::string& file) {
  if (!document.is_object()) return;  // the schema check says why
  const auto required = document.find("extensionsRequired");
  if (required == document.end() || !required->is_array()) return;
  for (const nlohmann::json& name : *required) {
    if (!name.is_string()) continue;
    const auto& text = name.get_ref<const std::string&>();
    if (text == kDracoExtension) throw SceneError(file + ": " + std::string(kDracoUnsupported));
    if (!IsAppearanceExtension(text)) {
      throw SceneError(file + ": requires extension " + gltf::Excerpt(text) +
                       ", which aasim does not support");
    }
  }
}

// tinygltf opens files through these callbacks only; they serve the bytes ReadResources has
// read, under the names ServeResources gave them, and nothing else.
using ServedFiles = std::map<std::string, std::vector<std::uint8_t>*>;

bool IsServed(const std::string& name, void* served) {
  return static_cast<const ServedFiles*>(served)->contains(name);
}

std::string SameName(const std::string& name, void*) { return name; }

bool Serve(std::vector<unsigned char>* out, std::string* error, const std::string& name,
           void* served) {
  const auto& files = *static_cast<const ServedFiles*>(served);
  const auto it = files.find(name);
  if (it == files.end()) {
    *error = "aasim serves only the resources it has read";
    return false;
  }
  out->swap(*it->second);  // each is asked for once; moving spares a copy
  return true;
}

bool RefuseWrite(std::string* error, const std::string&, const std::vector<unsigned char>&,
                 void*) {
  *error = "aasim writes no files";
  return false;
}

// Points every buffer and image uri of the document at bytes already read.
ServedFiles ServeResources(nlohmann::json& document, gltf::GltfResources& resources) {
  ServedFiles served;
  const auto serve = [&](const char* array, std::vector<std::vector<std::uint8_t>>& bytes) {
    if (!document.contains(array)) return;
    nlohmann::json& items = document[array];
    for (std::size_t i = 0; i < items.size(); ++i) {
      if (items[i].contains("bufferView")) continue;
      const std::string name = std::string("aasim-resource/") + array + "/" + std::to_string(i);
      items[i]["uri"] = name;
      served.emplace(name, &bytes.at(i));
    }
  };
  serve("buffers", resources.buffers);
  serve("images", resources.images);
  return served;
}

// tinygltf reads the checked document, re-serialised: what it parses is exactly what
// ValidateGltfSchema saw (duplicate keys resolved, URIs replaced).
tinygltf::Model BuildModel(nlohmann::json& document, gltf::GltfResources& resources,
                           const std::string& file, gltf::WarningLog& warnings) {
  ServedFiles served = ServeResources(document, resources);
  const std::string text = document.dump();
  if (text.size() > std::numeric_limits<unsigned int>::max()) {
    throw SceneError(file + ": the glTF document is too large for tinygltf");
  }
  tinygltf::TinyGLTF parser;
  parser.SetImageLoader(&KeepEncodedImage, nullptr);
  parser.SetFsCallbacks(tinygltf::FsCallbacks{&IsServed, &SameName, &Serve, &RefuseWrite, &served});
  tinygltf::Model model;
  std::string errors;
  std::string warningText;
  bool parsed = false;
  try {
    parsed = parser.LoadASCIIFromString(&model, &errors, &warningText, text.data(),
                                        static_cast<unsigned int>(text.size()), "");
  } catch (const std::exception& e) {
    throw SceneError(file + ": malformed glTF: " + OneLine(e.what()));
  }
  PrintWarnings(warnings, warningText);
  if (!parsed) {
    throw SceneError(file + ": cannot load glTF: " +
                     (errors.empty() ? std::string("unknown tinygltf error") : OneLine(errors)));
  }
  PrintWarnings(warnings, errors);
  return model;
}

}  // namespace

Scene LoadGltfFromMemory(std::span<const std::uint8_t> bytes, bool binary,
                         const std::filesystem::path& baseDir, std::string_view name,
                         float aspect) {
  const std::string file(name);
  gltf::WarningLog warnings(file);
  std::span<const std::uint8_t> jsonBytes = bytes;
  std::optional<std::span<const std::uint8_t>> bin;
  if (binary) {
    const gltf::GlbChunks chunks = gltf::SplitGlb(bytes, file, warnings);
    jsonBytes = chunks.json;
    bin = chunks.bin;
  }
  nlohmann::json document = gltf::ParseGltfJson(
      {reinterpret_cast<const char*>(jsonBytes.data()), jsonBytes.size()}, file);
  RequireSupportedExtensions(document, file);
  gltf::ValidateGltfSchema(document, binary, file, warnings);
  gltf::GltfResources resources = gltf::ReadResources(document, bin, baseDir, file, warnings);
  const tinygltf::Model model = BuildModel(document, resources, file, warnings);
  Scene scene = GltfFlattener(file, model, resources.imageOrigins, warnings).Flatten(aspect);
  scene.name = file;
  return scene;
}

Scene LoadGltf(const std::filesystem::path& path, float aspect) {
  const std::string extension = Lowercase(path.extension().string());
  if (extension != ".gltf" && extension != ".glb") {
    throw SceneError(path.string() + ": unknown scene file extension '" +
                     path.extension().string() +
                     "'; expected .gltf or .glb (or builtin:NAME for a built-in scene)");
  }
  const std::vector<std::uint8_t> bytes =
      gltf::ReadRegularFile(path, kMaxGltfFileBytes, path.string() + ": ");
  Scene scene = LoadGltfFromMemory(bytes, extension == ".glb", path.parent_path(), path.string(),
                                   aspect);
  scene.name = path.filename().string();
  return scene;
}

}  // namespace scenes
