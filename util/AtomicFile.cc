#include "util/AtomicFile.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace cg::util {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kTempSuffix = ".cgtmp";
std::atomic<unsigned> gCounter{0};

/// 8 hex digits naming this host (FNV-1a of its name): temp names stay short and safe.
const std::string& hostTag()
{
    static const std::string tag = [] {
        char name[256] = {};
        if (::gethostname(name, sizeof name - 1) != 0) std::strcpy(name, "unknown");
        std::uint32_t h = 2166136261u;
        for (const char* c = name; *c; ++c) h = (h ^ static_cast<unsigned char>(*c)) * 16777619u;
        char hex[9];
        std::snprintf(hex, sizeof hex, "%08x", h);
        return std::string(hex);
    }();
    return tag;
}

[[noreturn]] void fail(const fs::path& target, const std::string& why)
{
    throw std::runtime_error("cannot write '" + target.string() + "': " + why);
}

/// fsync of a file or directory; `what` failed when this returns false.
bool syncPath(const fs::path& p, int flags)
{
    const int fd = ::open(p.c_str(), flags | O_CLOEXEC);
    if (fd < 0) return false;
    const bool ok = ::fsync(fd) == 0;
    return ::close(fd) == 0 && ok;
}

/// Whether the temp file `name` belongs to a writer that is gone; false when in doubt.
bool isOrphan(const std::string& name, fs::file_time_type written)
{
    if (written < fs::file_time_type::clock::now() - std::chrono::hours(24)) return true;
    // ".<target>.<host>-<pid>-<n>.cgtmp"
    const std::size_t end = name.size() - kTempSuffix.size();
    const std::size_t dot = name.rfind('.', end - 1);
    if (dot == std::string::npos) return false;
    const std::string_view owner(name.data() + dot + 1, end - dot - 1);
    if (owner.size() < 10 || owner.substr(0, 8) != hostTag() || owner[8] != '-') return false;
    long pid = 0;
    const char* first = owner.data() + 9;
    const char* last = owner.data() + owner.size();
    const auto [stop, error] = std::from_chars(first, last, pid);
    if (error != std::errc() || stop == first || stop == last || *stop != '-' || pid <= 0)
        return false;
    return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

/// Writes `bytes` into the new temp file `fd` and closes it; "" or why it failed.
std::string writeAndClose(int fd, std::string_view bytes)
{
    std::string why;
    if (const int error = writeAllAt(fd, bytes.data(), bytes.size(), 0))
        why = std::string("write failed: ") + std::strerror(error);
    if (::close(fd) != 0 && why.empty()) why = std::string("close failed: ") + std::strerror(errno);
    return why;
}

/// The file `path` names once the symbolic links of its last component are followed (the
/// directories above may be links too: the kernel follows those when it renames).
fs::path followFinalLinks(const fs::path& path)
{
    fs::path p = path;
    for (int depth = 0; depth < 40; ++depth) {  // the kernel's own limit on nested links
        struct stat st {};
        if (::lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return p;
        std::error_code ec;
        const fs::path target = fs::read_symlink(p, ec);
        if (ec) fail(path, ec.message());
        p = target.is_absolute() ? target : p.parent_path() / target;
    }
    fail(path, std::strerror(ELOOP));
}

}  // namespace

AtomicOutput::AtomicOutput(fs::path target, fs::path tempDir) : mTarget(std::move(target))
{
    if (tempDir.empty()) tempDir = mTarget.parent_path();
    mTemp = tempDir / ("." + mTarget.filename().string() + "." + hostTag() + "-" +
                       std::to_string(::getpid()) + "-" + std::to_string(gCounter.fetch_add(1)) +
                       std::string(kTempSuffix));
}

AtomicOutput::~AtomicOutput()
{
    if (!mCommitted) {
        std::error_code ec;
        fs::remove(mTemp, ec);
    }
}

void AtomicOutput::commit(Flush flush)
{
    // The data must be on disk before the rename makes it visible: after a crash the
    // target would otherwise hold a whole-looking file with garbage inside.
    if (flush == Flush::ToDisk && !syncPath(mTemp, O_RDONLY))
        fail(mTarget, std::string("fsync failed: ") + std::strerror(errno));
    std::error_code ec;
    fs::rename(mTemp, mTarget, ec);
    if (ec) fail(mTarget, ec.message());
    mCommitted = true;
    // Makes the rename itself durable; the file is already whole, so a failure only costs
    // durability and is not reported.
    if (flush == Flush::ToDisk)
        syncPath(mTarget.parent_path().empty() ? fs::path(".") : mTarget.parent_path(), O_RDONLY);
}

int writeAllAt(int fd, const void* bytes, std::size_t size, std::uint64_t offset)
{
    const auto* p = static_cast<const unsigned char*>(bytes);
    while (size > 0) {
        const ssize_t n = ::pwrite(fd, p, size, static_cast<off_t>(offset));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return errno;
        if (n == 0) return EIO;  // no progress: the device takes no more
        p += n;
        size -= static_cast<std::size_t>(n);
        offset += static_cast<std::uint64_t>(n);
    }
    return 0;
}

bool fileHolds(const fs::path& file, std::string_view bytes)
{
    std::error_code ec;
    if (fs::file_size(file, ec) != bytes.size() || ec) return false;
    std::ifstream in(file, std::ios::binary);
    std::string existing(bytes.size(), '\0');
    return in.read(existing.data(), static_cast<std::streamsize>(existing.size())) &&
           existing == bytes;
}

void writeFileAtomically(const fs::path& target, std::string_view bytes, const fs::path& tempDir,
                         AtomicOutput::Flush flush)
{
    AtomicOutput out(target, tempDir);
    const int fd = ::open(out.tempPath().c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) fail(target, std::strerror(errno));
    if (const std::string why = writeAndClose(fd, bytes); !why.empty()) fail(target, why);
    out.commit(flush);
}

void saveFileAtomically(const fs::path& path, std::string_view bytes)
{
    // Renaming onto the link itself would leave its target without the edit and put a
    // regular file in place of the link.
    const fs::path target = followFinalLinks(path);
    struct stat old {};
    const bool replacing = ::stat(target.c_str(), &old) == 0;
    AtomicOutput out(target);
    const int fd = ::open(out.tempPath().c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) fail(path, std::strerror(errno));
    if (replacing) {
        // The new file is this process's, with the umask's mode: a 0600 graph would become
        // readable by all. The owner first, as chown clears the set-ID bits; only root may
        // give a file away, but an owner may still keep the group, so each is tried alone.
        if (old.st_uid != ::geteuid() || old.st_gid != ::getegid()) {
            if (::fchown(fd, old.st_uid, old.st_gid) != 0)
                static_cast<void>(::fchown(fd, static_cast<uid_t>(-1), old.st_gid));
        }
        if (::fchmod(fd, old.st_mode & 07777) != 0) {
            const std::string why = std::string("cannot keep its mode: ") + std::strerror(errno);
            ::close(fd);
            fail(path, why);
        }
    }
    if (const std::string why = writeAndClose(fd, bytes); !why.empty()) fail(path, why);
    out.commit();
}

std::size_t removeOrphanedTemporaries(const fs::path& dir)
{
    std::size_t removed = 0;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.size() <= kTempSuffix.size() + 1 || name[0] != '.' ||
            name.compare(name.size() - kTempSuffix.size(), kTempSuffix.size(), kTempSuffix) != 0)
            continue;
        std::error_code statError;
        if (!entry.is_regular_file(statError)) continue;
        const auto written = entry.last_write_time(statError);
        if (!statError && isOrphan(name, written) && fs::remove(entry.path(), statError)) ++removed;
    }
    return removed;
}

}  // namespace cg::util
