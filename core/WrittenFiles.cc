#include "core/WrittenFiles.h"

#include <fstream>
#include <sstream>
#include <vector>

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "core/CoreData.h"

namespace cg {

namespace {

namespace fs = std::filesystem;

/// The lines of a writer's "files" output (one path per line; empty when it wrote nothing).
std::vector<std::string> pathsIn(const std::string& files)
{
    std::vector<std::string> out;
    std::istringstream in(files);
    for (std::string line; std::getline(in, line);)
        if (!line.empty()) out.push_back(line);
    return out;
}

std::string absolutePath(const std::string& path)
{
    return fs::absolute(path).lexically_normal().string();
}

/// Size and content hash of a regular file; nullopt when it cannot be read whole.
std::optional<std::pair<std::uintmax_t, std::string>> fingerprint(const std::string& path)
{
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return std::nullopt;
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    Hasher h;
    std::vector<char> buffer(std::size_t(1) << 20);
    std::uintmax_t size = 0;
    while (in) {
        in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        const auto n = static_cast<std::size_t>(in.gcount());
        h.bytes(buffer.data(), n);
        size += n;
    }
    if (in.bad()) return std::nullopt;
    return std::make_pair(size, h.finish().hex());
}

}  // namespace

WrittenFiles::WrittenFiles(std::shared_ptr<DiskCache> cache, const fs::path& outDir)
    : mCache(std::move(cache)), mOutDir(fs::absolute(outDir).lexically_normal().string())
{
}

bool WrittenFiles::keepsRecords(const NodeDecl& decl)
{
    if (!decl.writesFiles || !decl.findOutput("files")) return false;
    for (const PortDecl& p : decl.outputs)
        if (p.type != "Text") return false;
    return true;
}

std::string WrittenFiles::recordName(const Key& key) const
{
    Hasher h;
    h.key(key).str(mOutDir);
    return "written-" + h.finish().hex();
}

void WrittenFiles::record(const Key& key, const OutputMap& outputs) const
{
    if (!mCache) return;
    nlohmann::json ports = nlohmann::json::object();
    nlohmann::json files = nlohmann::json::array();
    for (const auto& [port, value] : outputs) {
        const auto* text = dynamic_cast<const TextData*>(value.get());
        if (!text) return;
        ports[port] = text->value;
        if (port != "files") continue;
        for (const std::string& path : pathsIn(text->value)) {
            const auto print = fingerprint(path);
            if (!print) return;  // nothing to verify it by later
            files.push_back(
                {{"path", absolutePath(path)}, {"size", print->first}, {"xxh3", print->second}});
        }
    }
    try {
        mCache->storeRecord(
            recordName(key),
            {{"key", key.hex()}, {"out", mOutDir}, {"outputs", ports}, {"files", files}});
    } catch (const std::exception& e) {
        spdlog::warn("cannot record the files written for key {}: {}", key.hex(), e.what());
    }
}

std::optional<OutputMap> WrittenFiles::verified(const Key& key, const NodeDecl& decl) const
{
    if (!mCache) return std::nullopt;
    const auto record = mCache->loadRecord(recordName(key));
    if (!record) return std::nullopt;
    try {
        if (record->at("key").get<std::string>() != key.hex() ||
            record->at("out").get<std::string>() != mOutDir)
            return std::nullopt;
        OutputMap outputs;
        for (const PortDecl& port : decl.outputs)
            outputs[port.name] =
                std::make_shared<TextData>(record->at("outputs").at(port.name).get<std::string>());
        // The files must be exactly those the outputs name, each with its recorded bytes.
        const std::vector<std::string> named =
            pathsIn(record->at("outputs").at("files").get<std::string>());
        const nlohmann::json& files = record->at("files");
        if (!files.is_array() || files.size() != named.size()) return std::nullopt;
        for (std::size_t i = 0; i < named.size(); ++i) {
            if (files[i].at("path").get<std::string>() != absolutePath(named[i]))
                return std::nullopt;
            const auto print = fingerprint(named[i]);
            if (!print || print->first != files[i].at("size").get<std::uintmax_t>() ||
                print->second != files[i].at("xxh3").get<std::string>())
                return std::nullopt;
        }
        return outputs;
    } catch (const nlohmann::json::exception&) {
        return std::nullopt;  // forged or damaged: cook again
    }
}

}  // namespace cg
