#pragma once
// Internal to the glTF reader: the JSON document, parsed with a nesting bound and checked
// against the glTF 2.0 schema before tinygltf reads it. tinygltf takes a property of the wrong
// type for an absent one (a string "bufferView" draws nothing, a negative byteOffset reads as
// 0); after these checks every property it reads holds what the schema allows.

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "scenes/gltf_messages.h"

namespace scenes::gltf {

// Throws SceneError "FILE: cannot load glTF: malformed JSON: ..." (the parser's report,
// excerpted) for malformed JSON, and refuses arrays and objects nested deeper than
// kMaxGltfJsonDepth before the document is built.
nlohmann::json ParseGltfJson(std::string_view text, const std::string& file);

// Checks every property of the glTF 2.0 core schema, at every depth: JSON type, range, required
// properties, enum values, unique index lists, indices into the top-level arrays, and the
// rules of the spec's text aasim relies on (asset.version 2.x, minVersion at most 2.0, a
// bufferView inside its buffer, node matrices affine and not mixed with TRS, unit rotations,
// camera values that stay valid as floats, node values within kMaxGltfCoordinate, indices
// stored in a bufferView, extensionsRequired listed in extensionsUsed). Throws SceneError
// "FILE: POINTER: problem". Properties outside the schema get one warning per property name
// and kind of object. `binary`: a GLB, whose buffer 0 may omit its uri.
void ValidateGltfSchema(const nlohmann::json& document, bool binary, const std::string& file,
                        WarningLog& warnings);

}  // namespace scenes::gltf
