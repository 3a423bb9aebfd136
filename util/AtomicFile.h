#pragma once
/// Writing files so that nothing partial is ever left under the final name, and cleaning up
/// after writers that were killed. The one atomic writer: outputs and the disk cache use it.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>

namespace cg::util {

/// Write to tempPath(), then commit() renames it onto the target in one step. A writer
/// that throws before commit() leaves no file behind: the destructor removes the temp file.
///
/// Temp files are named ".<target name>.<host>-<pid>-<n>.cgtmp" (host: 8 hex digits of a
/// hash of the host name), so that a later run can tell a killed writer's orphan from a
/// live writer's file, even in a directory shared by several machines.
class AtomicOutput {
public:
    /// Whether commit() waits for the data to reach the disk.
    enum class Flush {
        ToDisk,  ///< fsync the file before the rename and the directory after: durable
        /// Only the rename: after an operating-system crash the target may hold a whole-looking
        /// file with garbage inside. For files whose readers verify a checksum of their own
        /// and drop a bad file (disk cache entries), where waiting for the disk on every
        /// write would only cost time.
        None,
    };

    /// `tempDir`: where the temp file goes; the target's directory when empty. It must be on
    /// the target's file system, so the rename cannot cross devices.
    explicit AtomicOutput(std::filesystem::path target, std::filesystem::path tempDir = {});
    ~AtomicOutput();
    AtomicOutput(const AtomicOutput&) = delete;
    AtomicOutput& operator=(const AtomicOutput&) = delete;

    const std::filesystem::path& tempPath() const { return mTemp; }
    const std::filesystem::path& target() const { return mTarget; }
    /// Flushes the temp file to disk (fsync; a failure throws, as the data may be lost) and
    /// renames it onto the target. Throws std::runtime_error naming the target.
    void commit(Flush flush = Flush::ToDisk);

private:
    std::filesystem::path mTarget;
    std::filesystem::path mTemp;
    bool mCommitted = false;
};

/// Writes all `size` bytes at `offset` of the open file `fd` (pwrite), resuming after short
/// writes and interrupts. Returns 0, or the errno of the failure.
int writeAllAt(int fd, const void* bytes, std::size_t size, std::uint64_t offset);

/// Writes `bytes` to `target` atomically. Throws std::runtime_error naming the file.
void writeFileAtomically(const std::filesystem::path& target, std::string_view bytes,
                         const std::filesystem::path& tempDir = {},
                         AtomicOutput::Flush flush = AtomicOutput::Flush::ToDisk);

/// Whether `file` already holds exactly `bytes` (a writer whose output would not change can
/// leave it, and its time stamp, alone); false when it cannot be read.
bool fileHolds(const std::filesystem::path& file, std::string_view bytes);

/// Saves `bytes` as the file `path` names, atomically, as an editor saves a document: through
/// symbolic links to the file they finally name (the link stays a link and its target gets
/// the bytes), keeping that file's permission bits and, where this process may set them, its
/// owner and group. A file that does not exist yet is made with mode 0666 less the umask.
/// Throws std::runtime_error naming `path`.
void saveFileAtomically(const std::filesystem::path& path, std::string_view bytes);

/// Removes the temp files in `dir` (not below it) that no live writer owns: those of this
/// host whose process has ended, and any older than a day (a writer on another host that
/// shares the directory finishes within minutes). Returns how many were removed; errors
/// are ignored, as cleaning is best effort.
std::size_t removeOrphanedTemporaries(const std::filesystem::path& dir);

}  // namespace cg::util
