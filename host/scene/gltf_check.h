// gltf_check.h — a glTF file's JSON as written, parsed and checked before tinygltf reads it
// (README, "Untrusted scenes").
//
// tinygltf 2.7 reads any file a URI names, and its messages then quote that file's size. Here
// every buffers[i].uri and images[i].uri is resolved inside the scene's folder first
// (SceneFolder::resolve), and an external buffer's size is compared with its byteLength, so that
// a refusal names the index and the key and no message quotes a file's size.
// Every error is a fen::Error "<file>: <glTF path>: <what>".
#pragma once

#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

namespace fen {

class SceneFolder;

// The document; "<file>: not a valid glTF file: ..." if the text is not one JSON object.
nlohmann::json parseGltfJson(const char* text, std::size_t size, const std::string& path);

void checkGltfJson(const nlohmann::json& doc, const std::string& path, const SceneFolder& folder);

}  // namespace fen
