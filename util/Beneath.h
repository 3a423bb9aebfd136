#pragma once
/// Keeping output files beneath their output directory: a symbolic link planted inside it
/// (`out/demo -> /elsewhere`) must not lead a writer to replace files outside it. Each
/// directory is resolved beneath the output directory (openat2 with RESOLVE_BENEATH where the
/// kernel has it, else an open whose result is checked against the directory's real path),
/// and a missing one is created in the directory found before it, never through a path.

#include <filesystem>
#include <string>

namespace cg::util {

/// Makes the place of the file `file` (relative, without "..") under `root`: creates `root`
/// if missing (following links: the user named it) and the directories of `file`'s path,
/// each found beneath `root`. Returns why not, or "" when the file can be written: a
/// directory of its path that leads out of `root` (through a symbolic link) or is not a
/// directory, a mkdir that failed, or a directory where the file would go.
std::string makeOutputPlace(const std::filesystem::path& root, const std::filesystem::path& file);

/// What makeOutputPlace would refuse, found without creating anything ("" when nothing that
/// exists is in the way).
std::string outputPlaceProblem(const std::filesystem::path& root,
                               const std::filesystem::path& file);

}  // namespace cg::util
