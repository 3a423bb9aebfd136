#pragma once
/// Writing output files so that nothing partial is ever left under the final name.

#include <filesystem>
#include <string_view>

namespace cg {

/// Write to tempPath(), then commit() renames it onto the target in one step. A writer
/// that throws before commit() leaves no file behind: the destructor removes the temp file.
class AtomicOutput {
public:
    explicit AtomicOutput(std::filesystem::path target);
    ~AtomicOutput();
    AtomicOutput(const AtomicOutput&) = delete;
    AtomicOutput& operator=(const AtomicOutput&) = delete;

    /// A unique name beside the target (same directory, so the rename cannot cross devices).
    const std::filesystem::path& tempPath() const { return mTemp; }
    const std::filesystem::path& target() const { return mTarget; }
    /// Flushes the temp file to disk and renames it onto the target.
    void commit();

private:
    std::filesystem::path mTarget;
    std::filesystem::path mTemp;
    bool mCommitted = false;
};

/// Writes `bytes` to `target` atomically. Throws std::runtime_error naming the file.
void writeFileAtomically(const std::filesystem::path& target, std::string_view bytes);

}  // namespace cg
