#include "core/CacheBound.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <system_error>
#include <vector>

#include "core/Error.h"

namespace cg {

namespace fs = std::filesystem;

namespace {

struct EntryFile {
    fs::path path;
    fs::file_time_type used;
    std::uint64_t bytes = 0;
};

/// Every regular *.cgc file under objects/, with its size and modification time.
std::vector<EntryFile> listEntries(const fs::path& root)
{
    std::vector<EntryFile> entries;
    std::error_code ec;
    const fs::path objects = root / "objects";
    if (!fs::is_directory(objects, ec)) return entries;
    for (fs::recursive_directory_iterator it(objects, ec), end; !ec && it != end;
         it.increment(ec)) {
        std::error_code statError;
        if (!it->is_regular_file(statError) || it->path().extension() != ".cgc") continue;
        EntryFile entry{it->path(), it->last_write_time(statError), 0};
        entry.bytes = it->file_size(statError);
        if (!statError) entries.push_back(std::move(entry));
    }
    return entries;
}

/// The multiplier of a size suffix ("", "K", "MB", "GiB", ...); 0 when it is not one.
std::uint64_t suffixScale(std::string suffix)
{
    for (char& c : suffix) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (suffix.size() > 1 && suffix.back() == 'B') suffix.pop_back();
    if (suffix.size() > 1 && suffix.back() == 'I') suffix.pop_back();
    if (suffix.empty() || suffix == "B") return 1;
    const std::string units = "KMGT";
    const auto at = units.find(suffix);
    if (suffix.size() != 1 || at == std::string::npos) return 0;
    return std::uint64_t(1) << (10 * (at + 1));
}

}  // namespace

CacheUsage cacheUsage(const fs::path& root)
{
    CacheUsage usage;
    for (const EntryFile& entry : listEntries(root)) {
        usage.bytes += entry.bytes;
        ++usage.entries;
    }
    return usage;
}

CacheUsage pruneCache(const fs::path& root, std::uint64_t maxBytes)
{
    std::vector<EntryFile> entries = listEntries(root);
    std::sort(entries.begin(), entries.end(), [](const EntryFile& a, const EntryFile& b) {
        return a.used != b.used ? a.used < b.used : a.path < b.path;
    });
    std::uint64_t total = 0;
    for (const EntryFile& entry : entries) total += entry.bytes;
    CacheUsage removed;
    for (const EntryFile& entry : entries) {
        if (total <= maxBytes) break;
        std::error_code ec;
        if (fs::remove(entry.path, ec)) {
            removed.bytes += entry.bytes;
            ++removed.entries;
        }
        total -= entry.bytes;  // gone either way: removed here or by another process
    }
    return removed;
}

std::uint64_t parseByteSize(std::string_view text, std::string_view where)
{
    const std::string s(text);
    const auto bad = [&] {
        return InputError(std::string(where), "'" + s +
                                                  "' is not a size: give bytes or a number with "
                                                  "K, M, G or T (powers of 1024), e.g. 20G");
    };
    std::size_t end = 0;
    double number = 0;
    try {
        number = std::stod(s, &end);
    } catch (const std::exception&) {
        throw bad();
    }
    const std::uint64_t scale = suffixScale(s.substr(end));
    const double bytes = number * static_cast<double>(scale);
    if (scale == 0 || !std::isfinite(bytes) || bytes < 0 || bytes >= 0x1p63) throw bad();
    return static_cast<std::uint64_t>(bytes);
}

}  // namespace cg
