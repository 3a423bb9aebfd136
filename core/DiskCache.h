#pragma once
/// On-disk cache of cooked outputs by content key, shared safely by several processes.
///
/// Layout under the root directory:
///   objects/<first 2 hex digits>/<32 hex digits>.cgc   one entry per key
///   records/<name>.json                                small JSON records (why-cooked data)
///   tmp/                                               files being written
///
/// An entry is written to tmp/ under a unique name, then renamed into place, so a reader
/// sees either no entry or a whole one. Entries are not fsynced (records are): one torn by
/// an operating-system crash fails the checksums below and reads as a miss. Two processes
/// storing the same key both succeed (the last rename wins, with identical bytes). The
/// entry header holds the full key, the payload length and checksums; load() verifies all
/// of them and treats any mismatch (truncation, flipped bytes, foreign file) as a miss: it
/// logs a warning, removes the entry and the caller recooks.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/Hash.h"
#include "core/Node.h"
#include "util/AtomicFile.h"

namespace cg {

class Registry;

class DiskCache {
public:
    /// Creates the directory layout if needed; throws InputError (naming the directory)
    /// when it cannot be created or written.
    explicit DiskCache(std::filesystem::path root);

    const std::filesystem::path& root() const { return mRoot; }

    /// The stored outputs for `key`, rebuilt through the registry's data types; nullopt
    /// when absent or damaged (damaged entries are removed, with a warning).
    /// `outputs`, when given, are the node's declared output ports: an entry with other
    /// names or types is damaged. I/O errors and entries too large for the memory available
    /// now are misses that leave the entry in place. A load refreshes the entry's
    /// modification time, which pruneCache (CacheBound.h) reads as its last use.
    std::optional<OutputMap> load(const Key& key, const Registry& registry,
                                  const std::vector<PortDecl>* outputs = nullptr) const;
    /// Stores the outputs. Returns false (storing nothing) when a value's type cannot be
    /// serialized. I/O failures are logged and return false: a cache is an optimisation.
    bool store(const Key& key, const OutputMap& outputs) const;
    bool contains(const Key& key) const;

    /// Where the entry for `key` lives (for tests and tools).
    std::filesystem::path entryPath(const Key& key) const;

    /// Small JSON side records, written atomically the same way; nullopt if absent/invalid.
    std::optional<nlohmann::json> loadRecord(const std::string& name) const;
    void storeRecord(const std::string& name, const nlohmann::json& record) const;

    /// The bytes of a whole entry file into `buffer` (cleared first, its capacity kept; public
    /// for tests and the fuzzer); false if an output cannot be serialized.
    static bool encodeEntry(const Key& key, const OutputMap& outputs,
                            std::vector<unsigned char>& buffer);
    /// Parses a whole entry file; throws std::runtime_error with the byte offset of the
    /// first inconsistency (std::bad_alloc passes through).
    static OutputMap decodeEntry(const Key& key, const unsigned char* data, std::size_t size,
                                 const Registry& registry,
                                 const std::vector<PortDecl>* outputs = nullptr);

private:
    static OutputMap decodePayload(const unsigned char* payload, std::size_t payloadSize,
                                   std::uint64_t checksum, const Registry& registry,
                                   const std::vector<PortDecl>* outputs);
    /// Writes bytes to tmp/ then renames onto `target`.
    bool writeAtomically(const std::filesystem::path& target, const void* data, std::size_t size,
                         util::AtomicOutput::Flush flush) const;
    std::filesystem::path mRoot;
};

}  // namespace cg
