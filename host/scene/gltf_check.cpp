// gltf_check.cpp — checks on a glTF document's JSON before tinygltf reads it (gltf_check.h).
#include "scene/gltf_check.h"

#include <filesystem>

#include "scene/scene_files.h"
#include "util/error.h"

namespace fen {

namespace {

// buffers[i].uri / images[i].uri: inside the folder, and an external buffer exactly byteLength
// long (tinygltf's rule; its own message would quote the file's size).
void checkUris(const nlohmann::json& doc, const std::string& path, const SceneFolder& folder)
{
    for (const char* key : {"buffers", "images"}) {
        const auto list = doc.find(key);
        if (list == doc.end() || !list->is_array())
            continue;
        const bool buffer = std::string(key) == "buffers";
        for (std::size_t i = 0; i < list->size(); ++i) {
            const nlohmann::json& item = (*list)[i];
            const std::string where = cat(path, ": ", key, "[", i, "]");
            if (!item.is_object() || !item.contains("uri"))
                continue;
            const nlohmann::json& uri = item["uri"];
            if (!uri.is_string())
                throw Error(cat(where, ".uri: must be a string"));
            if (uri.get<std::string>().empty())
                continue;  // no file: a GLB's BIN chunk (tinygltf reports it elsewhere)
            // Images are ignored: one missing is no reason to refuse the scene.
            const std::string file = folder.resolve(uri.get<std::string>(), where + ".uri", buffer);
            if (!buffer || file.empty())
                continue;
            const auto length = item.find("byteLength");
            std::error_code ec;
            const std::uintmax_t size = std::filesystem::file_size(file, ec);
            if (length != item.end() && length->is_number_unsigned() &&
                (ec || size != length->get<std::uint64_t>()))
                throw Error(cat(where, ".uri: '", printable(uri.get<std::string>()),
                                "' is not byteLength ", length->get<std::uint64_t>(), " bytes long"));
        }
    }
}

}  // namespace

nlohmann::json parseGltfJson(const char* text, std::size_t size, const std::string& path)
{
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(text, text + size);
    } catch (const nlohmann::json::exception& e) {
        throw Error(cat(path, ": not a valid glTF file: ", printable(e.what())));
    }
    if (!doc.is_object())
        throw Error(cat(path, ": not a valid glTF file: the top level is not a JSON object"));
    return doc;
}

void checkGltfJson(const nlohmann::json& doc, const std::string& path, const SceneFolder& folder)
{
    checkUris(doc, path, folder);
}

}  // namespace fen
