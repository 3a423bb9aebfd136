#pragma once
/// What a writer wrote, so that a rerun sharing the disk cache can skip it: for each writer
/// cook, a record of the absolute paths in its "files" output with each file's size and
/// XXH3 hash. A rerun whose writer has the same key and the same output directory, and
/// whose files are all still there with the same bytes, takes the recorded outputs instead
/// of cooking, and nothing upstream of it cooks for that frame. A record that is missing,
/// unreadable or forged, or a file that changed, is a miss: the writer cooks and writes
/// again. Without a disk cache nothing is recorded and writers cook on every run.
///
/// Records are the disk cache's side records ("written-<hash of key and out dir>"), stored
/// after the writer's own files are in place, so a run killed in between leaves none.

#include <filesystem>
#include <memory>
#include <optional>

#include "core/DiskCache.h"
#include "core/Hash.h"
#include "core/Node.h"

namespace cg {

class WrittenFiles {
public:
    /// `cache` may be null: then nothing is recorded or verified.
    WrittenFiles(std::shared_ptr<DiskCache> cache, const std::filesystem::path& outDir);

    /// Whether `decl` keeps records: a writer whose outputs are Text ports, one of them
    /// "files" (the writerDecl convention). LogText, which prints, always cooks.
    static bool keepsRecords(const NodeDecl& decl);

    /// Records a writer's outputs after it cooked. Failures are logged, never thrown: a
    /// missing record only costs a rewrite.
    void record(const Key& key, const OutputMap& outputs) const;

    /// The recorded outputs when every file they name verifies; nullopt otherwise.
    std::optional<OutputMap> verified(const Key& key, const NodeDecl& decl) const;

private:
    std::string recordName(const Key& key) const;

    std::shared_ptr<DiskCache> mCache;
    std::string mOutDir;  ///< absolute, normalised
};

}  // namespace cg
