// glTF 2.0 import: tinygltf parses the file, this module validates every accessor it touches,
// flattens the scene's node tree into world-space triangle lists with their base colour materials
// and sRGB-decoded textures, and picks the file's camera. Any defect is a SceneError.

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <optional>
#include <set>
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

// GLB header: magic, version, total length; then the JSON chunk's length and type.
constexpr std::size_t kGlbJsonStart = 20;
constexpr std::uint32_t kGlbJsonChunkType = 0x4E4F534Au;  // "JSON"

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
  return joined;
}

void PrintWarnings(const std::filesystem::path& path, const std::string& text) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::cerr << path.string() << ": warning: " << line << '\n';
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
  return label.append("'").append(mesh.name).append("'");
}

bool IsFinite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool IsAppearanceExtension(const std::string& name) {
  return std::any_of(kAppearancePrefixes.begin(), kAppearancePrefixes.end(),
                     [&](std::string_view prefix) { return name.starts_with(prefix); });
}

// Only base colour images are ever drawn, so decoding waits until a material needs one: here
// the encoded bytes of a uri image (a file or data URI, read by tinygltf into a buffer of exactly
// `size` bytes) are kept as they are. A bufferView image is left alone because tinygltf does not
// check that view against its buffer; the flattener reads it through its own checks.
bool KeepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView >= 0 || size <= 0) return true;
  image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

bool IsPngOrJpeg(const tinygltf::Image& image) {
  if (image.mimeType == "image/png" || image.mimeType == "image/jpeg") return true;
  const std::string extension = Lowercase(std::filesystem::path(image.uri).extension().string());
  return !image.uri.starts_with("data:") &&
         (extension == ".png" || extension == ".jpg" || extension == ".jpeg");
}

std::string FormatNumber(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// One warning per extension the file uses: each says what aasim draws instead.
std::string IgnoredExtensionMessage(const std::string& name) {
  std::string text = "extension " + name + " is ignored";
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

class GltfFlattener {
 public:
  GltfFlattener(const std::filesystem::path& path, const tinygltf::Model& model)
      : path_(path), model_(model) {}

  // Everything but the scene's name.
  Scene Flatten(float aspect) {
    CheckRequiredExtensions();
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
    throw SceneError(path_.string() + ": " + problem);
  }

  // Each distinct text is printed once per file, however many elements it concerns.
  void Warn(const std::string& text) {
    if (warned_.insert(text).second) std::cerr << path_.string() << ": warning: " << text << '\n';
  }

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

  void CheckRequiredExtensions() const {
    for (const std::string& name : model_.extensionsRequired) {
      if (name == kDracoExtension) Fail(std::string(kDracoUnsupported));
      if (!IsAppearanceExtension(name)) {
        Fail("requires extension " + name + ", which aasim does not support");
      }
    }
  }

  std::vector<int> RootNodes() const {
    if (model_.defaultScene >= 0) {
      if (static_cast<std::size_t>(model_.defaultScene) >= model_.scenes.size()) {
        Fail("default scene " + std::to_string(model_.defaultScene) + " does not exist (" +
             std::to_string(model_.scenes.size()) + " scenes)");
      }
      return model_.scenes[static_cast<std::size_t>(model_.defaultScene)].nodes;
    }
    if (!model_.scenes.empty()) return model_.scenes.front().nodes;
    return ParentlessNodes();
  }

  // Without a scene, glTF leaves the roots implicit: every node that is nobody's child.
  std::vector<int> ParentlessNodes() const {
    std::vector<bool> isChild(model_.nodes.size(), false);
    for (const tinygltf::Node& node : model_.nodes) {
      for (int child : node.children) {
        if (child >= 0 && static_cast<std::size_t>(child) < isChild.size()) {
          isChild[static_cast<std::size_t>(child)] = true;
        }
      }
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
    const glm::dmat4 world = parentWorld * LocalTransform(node, nodeIndex);
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
    if (index < 0 || static_cast<std::size_t>(index) >= model_.nodes.size()) {
      Fail("node " + std::to_string(index) + " does not exist (" +
           std::to_string(model_.nodes.size()) + " nodes)");
    }
    return model_.nodes[static_cast<std::size_t>(index)];
  }

  glm::dmat4 LocalTransform(const tinygltf::Node& node, int index) const {
    const std::string where = "node " + std::to_string(index);
    glm::dmat4 local(1.0);
    if (!node.matrix.empty()) {
      ExpectSize(node.matrix, 16, where + " matrix");
      local = glm::make_mat4(node.matrix.data());  // both column-major
    } else {
      local = TranslationRotationScale(node, where);
    }
    for (int column = 0; column < 4; ++column) {
      for (int row = 0; row < 4; ++row) {
        if (!std::isfinite(local[column][row])) Fail(where + " has a non-finite transform");
      }
    }
    return local;
  }

  glm::dmat4 TranslationRotationScale(const tinygltf::Node& node, const std::string& where) const {
    glm::dmat4 local(1.0);
    if (!node.translation.empty()) {
      ExpectSize(node.translation, 3, where + " translation");
      local = glm::translate(local, glm::make_vec3(node.translation.data()));
    }
    if (!node.rotation.empty()) {
      ExpectSize(node.rotation, 4, where + " rotation");
      const std::vector<double>& r = node.rotation;  // glTF order: x, y, z, w
      glm::dquat rotation(r[3], r[0], r[1], r[2]);
      const double length = glm::length(rotation);
      if (!(length > 0.0)) Fail(where + " rotation is not a valid quaternion");
      // Exporters write unit quaternions rounded to float; renormalising removes the tiny
      // scale that rounding would otherwise add.
      local *= glm::mat4_cast(rotation / length);
    }
    if (!node.scale.empty()) {
      ExpectSize(node.scale, 3, where + " scale");
      local = glm::scale(local, glm::make_vec3(node.scale.data()));
    }
    return local;
  }

  void ExpectSize(const std::vector<double>& values, std::size_t size,
                  const std::string& what) const {
    if (values.size() != size) {
      Fail(what + " has " + std::to_string(values.size()) + " numbers, expected " +
           std::to_string(size));
    }
  }

  void AddMeshInstance(int meshIndex, const glm::dmat4& world) {
    if (static_cast<std::size_t>(meshIndex) >= model_.meshes.size()) {
      Fail("mesh " + std::to_string(meshIndex) + " does not exist (" +
           std::to_string(model_.meshes.size()) + " meshes)");
    }
    ++meshInstances_;
    const tinygltf::Mesh& mesh = model_.meshes[static_cast<std::size_t>(meshIndex)];
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
    Mesh mesh;
    mesh.name = std::move(name);
    mesh.positions = ReadVec3(positionIt->second, {"POSITION", TINYGLTF_TYPE_VEC3}, where);
    CheckFinite(mesh.positions, "position", where);
    const auto normalIt = primitive.attributes.find("NORMAL");
    if (normalIt != primitive.attributes.end()) {
      mesh.normals = ReadVec3(normalIt->second, {"NORMAL", TINYGLTF_TYPE_VEC3}, where);
      CheckFinite(mesh.normals, "normal", where);
      if (mesh.normals.size() != mesh.positions.size()) {
        Fail(where + ": " + std::to_string(mesh.normals.size()) + " normals for " +
             std::to_string(mesh.positions.size()) + " positions");
      }
    }
    const auto texcoordIt = primitive.attributes.find("TEXCOORD_0");
    if (texcoordIt != primitive.attributes.end()) {
      mesh.texcoords = ReadTexcoords(texcoordIt->second, where);
      if (mesh.texcoords.size() != mesh.positions.size()) {
        Fail(where + ": " + std::to_string(mesh.texcoords.size()) + " texture coordinates for " +
             std::to_string(mesh.positions.size()) + " positions");
      }
    }
    mesh.material = SceneMaterial(primitive.material, !mesh.texcoords.empty(), where);
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

  // --- Materials and textures -----------------------------------------------------------------

  // The Scene::materials index for a primitive's glTF material (-1 stays -1). A textured
  // material on a primitive without TEXCOORD_0 becomes an untextured copy: there is nothing to
  // sample the texture with.
  int SceneMaterial(int index, bool hasTexcoords, const std::string& where) {
    if (index < 0) return -1;
    if (static_cast<std::size_t>(index) >= model_.materials.size()) {
      Fail(where + ": material " + std::to_string(index) + " does not exist (" +
           std::to_string(model_.materials.size()) + " materials)");
    }
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
    const tinygltf::Material& source = model_.materials[static_cast<std::size_t>(index)];
    std::string where = "material ";
    if (source.name.empty()) {
      where.append(std::to_string(index));
    } else {
      where.append("'").append(source.name).append("'");
    }
    const std::vector<double>& factor = source.pbrMetallicRoughness.baseColorFactor;
    ExpectSize(factor, 4, where + " baseColorFactor");
    if (!std::all_of(factor.begin(), factor.end(), [](double v) { return std::isfinite(v); })) {
      Fail(where + ": baseColorFactor has a non-finite component");
    }
    WarnUnmodelledMaps(source);
    Material material;
    material.name = source.name.empty() ? where : source.name;
    material.baseColourFactor = glm::vec4(glm::dvec4(factor[0], factor[1], factor[2], factor[3]));
    material.baseColourTexture =
        BaseColourTexture(source.pbrMetallicRoughness.baseColorTexture, where);
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

  int BaseColourTexture(const tinygltf::TextureInfo& info, const std::string& where) {
    if (info.index < 0) return -1;
    if (info.texCoord != 0) {
      Warn("base colour textures on TEXCOORD_" + std::to_string(info.texCoord) +
           " are not supported (TEXCOORD_0 only): their materials use the base colour factor");
      return -1;
    }
    if (static_cast<std::size_t>(info.index) >= model_.textures.size()) {
      Fail(where + ": baseColorTexture refers to texture " + std::to_string(info.index) +
           ", which does not exist (" + std::to_string(model_.textures.size()) + " textures)");
    }
    const tinygltf::Texture& texture = model_.textures[static_cast<std::size_t>(info.index)];
    const std::string textureName = "texture " + std::to_string(info.index);
    CheckSampler(texture.sampler, textureName);
    if (texture.source < 0) {
      Warn("textures without a PNG or JPEG source image are dropped: their materials use the "
           "base colour factor");
      return -1;
    }
    if (static_cast<std::size_t>(texture.source) >= model_.images.size()) {
      Fail(textureName + " refers to image " + std::to_string(texture.source) +
           ", which does not exist (" + std::to_string(model_.images.size()) + " images)");
    }
    // Textures differ from their image only by the sampler, which aasim does not model.
    const auto [it, inserted] = imageTexture_.try_emplace(texture.source, -1);
    if (inserted) {
      std::optional<Texture> decoded = DecodeImage(texture.source);
      if (decoded) {
        textures_.push_back(std::move(*decoded));
        it->second = static_cast<int>(textures_.size()) - 1;
      }
    }
    return it->second;
  }

  void CheckSampler(int index, const std::string& textureName) {
    if (index < 0) return;
    if (static_cast<std::size_t>(index) >= model_.samplers.size()) {
      Fail(textureName + " refers to sampler " + std::to_string(index) +
           ", which does not exist (" + std::to_string(model_.samplers.size()) + " samplers)");
    }
    const tinygltf::Sampler& sampler = model_.samplers[static_cast<std::size_t>(index)];
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

  // nullopt (with a warning) for a format stb_image cannot decode; a PNG or JPEG that fails to
  // decode, or an image file that could not be read, is an error.
  std::optional<Texture> DecodeImage(int index) {
    const tinygltf::Image& image = model_.images[static_cast<std::size_t>(index)];
    const bool external = !image.uri.empty() && !image.uri.starts_with("data:");
    std::string name = !image.name.empty() ? image.name
                       : external          ? image.uri
                                           : "image " + std::to_string(index);
    std::string where = "image " + std::to_string(index);
    if (!image.name.empty() || external) where.append(" '").append(name).append("'");
    const std::span<const unsigned char> encoded = EncodedImage(image, where);
    if (encoded.empty()) {
      Fail(where + (external ? ": cannot read the image file" : ": has no image data"));
    }
    if (encoded.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
      Fail(where + ": " + std::to_string(encoded.size()) + " bytes is too large to decode");
    }
    tinygltf::Image decoded;
    std::string errors;
    std::string warnings;
    if (!tinygltf::LoadImageData(&decoded, index, &errors, &warnings, 0, 0, encoded.data(),
                                 static_cast<int>(encoded.size()), nullptr)) {
      if (IsPngOrJpeg(image)) Fail(where + ": cannot decode: " + OneLine(errors));
      Warn("images that are not PNG or JPEG are dropped (first: " + where +
           "): their materials use the base colour factor");
      return std::nullopt;
    }
    try {
      return DecodeTexels(std::move(name), decoded.width, decoded.height, decoded.component,
                          decoded.bits, decoded.image, ColourEncoding::Srgb);
    } catch (const SceneError& e) {
      Fail(where + ": " + e.what());
    }
  }

  std::span<const unsigned char> EncodedImage(const tinygltf::Image& image,
                                              const std::string& where) const {
    if (image.bufferView < 0) return image.image;
    if (static_cast<std::size_t>(image.bufferView) >= model_.bufferViews.size()) {
      Fail(where + " refers to bufferView " + std::to_string(image.bufferView) +
           ", which does not exist");
    }
    const tinygltf::BufferView& view =
        model_.bufferViews[static_cast<std::size_t>(image.bufferView)];
    return {BufferViewData(view, image.bufferView, where), view.byteLength};
  }

  // --- Camera -----------------------------------------------------------------------------------

  void NoteCamera(int cameraIndex, int nodeIndex, const glm::dmat4& world) {
    if (static_cast<std::size_t>(cameraIndex) >= model_.cameras.size()) {
      Fail("node " + std::to_string(nodeIndex) + " refers to camera " +
           std::to_string(cameraIndex) + ", which does not exist (" +
           std::to_string(model_.cameras.size()) + " cameras)");
    }
    const std::string& type = model_.cameras[static_cast<std::size_t>(cameraIndex)].type;
    if (type == "perspective") {
      if (!perspective_) perspective_ = CameraInstance{cameraIndex, nodeIndex, world};
    } else if (type == "orthographic") {
      if (!orthographic_) orthographic_ = CameraInstance{cameraIndex, nodeIndex, world};
    } else {
      Fail("camera " + std::to_string(cameraIndex) + " has type '" + type +
           "', expected perspective or orthographic");
    }
  }

  Camera MakeCamera(const Bounds& bounds, float aspect) {
    if (perspective_) return FileCamera(*perspective_, bounds, aspect);
    if (orthographic_) {
      Warn("orthographic camera " + std::to_string(orthographic_->camera) +
           " is not supported (aasim renders perspective views): framing the scene bounds instead");
    }
    return FrameBounds(bounds, aspect);
  }

  Camera FileCamera(const CameraInstance& instance, const Bounds& bounds, float aspect) {
    const tinygltf::Camera& source = model_.cameras[static_cast<std::size_t>(instance.camera)];
    const tinygltf::PerspectiveCamera& lens = source.perspective;
    std::string where = "camera " + std::to_string(instance.camera);
    if (!source.name.empty()) where.append(" '").append(source.name).append("'");
    if (!(std::isfinite(lens.yfov) && lens.yfov > 0.0 && lens.yfov < std::numbers::pi)) {
      Fail(where + ": yfov " + FormatNumber(lens.yfov) + " is not between 0 and pi");
    }
    if (!(std::isfinite(lens.znear) && lens.znear > 0.0)) {
      Fail(where + ": znear " + FormatNumber(lens.znear) + " is not positive");
    }
    const bool infinite = lens.zfar == 0.0;
    if (!infinite && !(std::isfinite(lens.zfar) && lens.zfar > lens.znear)) {
      Fail(where + ": zfar " + FormatNumber(lens.zfar) + " is not beyond znear " +
           FormatNumber(lens.znear));
    }
    // glTF cameras look down their node's -z with +y up.
    const glm::dvec3 eye(instance.world[3]);
    const glm::dvec3 back(instance.world[2]);
    const glm::dvec3 right = glm::cross(-back, glm::dvec3(instance.world[1]));
    if (!IsFinite(glm::vec3(eye)) || !(glm::length(back) > 0.0) || !(glm::length(right) > 0.0)) {
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
      const glm::dvec4 p = world * glm::dvec4(glm::dvec3(mesh.positions[i]), 1.0);
      mesh.positions[i] = glm::vec3(p);
      if (!IsFinite(mesh.positions[i])) {
        Fail(where + ": vertex " + std::to_string(i) +
             " has a non-finite position after its node transforms " +
             FormatVec3(mesh.positions[i]));
      }
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

  const tinygltf::Accessor& Accessor(int index, std::string_view role,
                                     const std::string& where) const {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size()) {
      Fail(where + ": " + std::string(role) + " accessor " + std::to_string(index) +
           " does not exist (" + std::to_string(model_.accessors.size()) + " accessors)");
    }
    return model_.accessors[static_cast<std::size_t>(index)];
  }

  // Checks the accessor's type and that all its elements lie inside its bufferView and buffer.
  ElementView ViewElements(int index, const AccessorUse& use, std::size_t elementSize,
                           const std::string& where) const {
    const tinygltf::Accessor& accessor = Accessor(index, use.role, where);
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
    if (static_cast<std::size_t>(accessor.bufferView) >= model_.bufferViews.size()) {
      Fail(name + " refers to bufferView " + std::to_string(accessor.bufferView) +
           ", which does not exist");
    }
    const tinygltf::BufferView& bufferView =
        model_.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
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
    if (bufferView.buffer < 0 ||
        static_cast<std::size_t>(bufferView.buffer) >= model_.buffers.size()) {
      Fail(viewName + " refers to buffer " + std::to_string(bufferView.buffer) +
           ", which does not exist");
    }
    const std::vector<unsigned char>& data =
        model_.buffers[static_cast<std::size_t>(bufferView.buffer)].data;
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
    const tinygltf::Accessor& accessor = Accessor(index, use.role, where);
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
    const tinygltf::Accessor& accessor = Accessor(index, use.role, where);
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
    const tinygltf::Accessor& accessor = Accessor(index, use.role, where);
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

  void WarnSkipped() const {
    for (const SkippedKind& kind : skipped_) {
      if (kind.count == 0) continue;
      std::cerr << path_.string() << ": warning: skipped " << kind.count << ' ' << kind.name
                << " primitive" << (kind.count == 1 ? "" : "s")
                << " (only triangles have coverage)\n";
    }
  }

  const std::filesystem::path& path_;
  const tinygltf::Model& model_;
  std::vector<Mesh> meshes_;
  std::vector<Material> materials_;
  std::vector<Texture> textures_;
  std::map<int, int> materialIndex_;      // glTF material -> materials_
  std::map<int, int> untexturedVariant_;  // materials_ entry -> its untextured copy
  std::map<int, int> imageTexture_;       // glTF image -> textures_, -1 when dropped
  std::optional<CameraInstance> perspective_;
  std::optional<CameraInstance> orthographic_;
  std::set<std::string> warned_;
  std::size_t nodeInstances_ = 0;
  std::size_t meshInstances_ = 0;
  // Indexed by glTF mode; the triangle modes' slots stay unused.
  std::array<SkippedKind, 4> skipped_{SkippedKind{"POINTS"}, SkippedKind{"LINES"},
                                      SkippedKind{"LINE_LOOP"}, SkippedKind{"LINE_STRIP"}};
};

// The JSON text of a .gltf, or the JSON chunk of a .glb; empty when the file is unreadable.
std::string JsonText(const std::filesystem::path& path, bool binary) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) return {};
  std::string bytes(static_cast<std::size_t>(size), '\0');
  std::ifstream file(path, std::ios::binary);
  if (!file.read(bytes.data(), static_cast<std::streamsize>(bytes.size()))) return {};
  if (!binary) return bytes;
  if (bytes.size() < kGlbJsonStart) return {};
  std::uint32_t chunkLength = 0;
  std::uint32_t chunkType = 0;
  std::memcpy(&chunkLength, bytes.data() + 12, sizeof(chunkLength));
  std::memcpy(&chunkType, bytes.data() + 16, sizeof(chunkType));
  if (chunkType != kGlbJsonChunkType || chunkLength > bytes.size() - kGlbJsonStart) return {};
  return bytes.substr(kGlbJsonStart, chunkLength);
}

// tinygltf rejects Draco files before we see the model (their accessors lack bufferViews), so a
// failed load is re-read here to give the real reason.
bool RequiresDraco(const std::filesystem::path& path, bool binary) {
  const nlohmann::json document =
      nlohmann::json::parse(JsonText(path, binary), nullptr, /*allow_exceptions=*/false);
  if (!document.is_object()) return false;
  const auto required = document.find("extensionsRequired");
  if (required == document.end() || !required->is_array()) return false;
  return std::any_of(required->begin(), required->end(), [](const nlohmann::json& name) {
    return name.is_string() && name.get<std::string>() == kDracoExtension;
  });
}

tinygltf::Model ParseFile(const std::filesystem::path& path, bool binary) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) throw SceneError(path.string() + ": no such file");
  if (!std::filesystem::is_regular_file(path, error)) {
    throw SceneError(path.string() + ": not a regular file");
  }
  tinygltf::TinyGLTF parser;
  parser.SetImageLoader(&KeepEncodedImage, nullptr);
  tinygltf::Model model;
  std::string errors;
  std::string warnings;
  bool parsed = false;
  try {
    parsed = binary ? parser.LoadBinaryFromFile(&model, &errors, &warnings, path.string())
                    : parser.LoadASCIIFromFile(&model, &errors, &warnings, path.string());
  } catch (const std::exception& e) {
    // tinygltf lets some JSON type errors escape as exceptions instead of reporting them.
    throw SceneError(path.string() + ": malformed glTF: " + OneLine(e.what()));
  }
  PrintWarnings(path, warnings);
  if (!parsed) {
    if (RequiresDraco(path, binary)) {
      throw SceneError(path.string() + ": " + std::string(kDracoUnsupported));
    }
    throw SceneError(path.string() + ": cannot load glTF: " +
                     (errors.empty() ? std::string("unknown tinygltf error") : OneLine(errors)));
  }
  PrintWarnings(path, errors);
  return model;
}

}  // namespace

Scene LoadGltf(const std::filesystem::path& path, float aspect) {
  const std::string extension = Lowercase(path.extension().string());
  if (extension != ".gltf" && extension != ".glb") {
    throw SceneError(path.string() + ": unknown scene file extension '" +
                     path.extension().string() +
                     "'; expected .gltf or .glb (or builtin:NAME for a built-in scene)");
  }
  const tinygltf::Model model = ParseFile(path, extension == ".glb");
  Scene scene = GltfFlattener(path, model).Flatten(aspect);
  scene.name = path.filename().string();
  return scene;
}

}  // namespace scenes
