#include "util/Beneath.h"

#include <fcntl.h>
#include <linux/openat2.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <string_view>
#include <system_error>

namespace cg::util {

namespace fs = std::filesystem;

namespace {

/// An open file descriptor, closed when it goes.
class Fd {
public:
    explicit Fd(int fd = -1) : mFd(fd) {}
    ~Fd()
    {
        if (mFd >= 0) ::close(mFd);
    }
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
    Fd& operator=(Fd&& other) noexcept
    {
        std::swap(mFd, other.mFd);
        return *this;
    }
    int get() const { return mFd; }

private:
    int mFd;
};

/// Whether the open directory `fd` is `rootReal` (a real path) or lies below it.
bool liesBeneath(int fd, const std::string& rootReal)
{
    const std::string link = "/proc/self/fd/" + std::to_string(fd);
    char buffer[PATH_MAX];
    const ssize_t n = ::readlink(link.c_str(), buffer, sizeof buffer);
    if (n <= 0 || static_cast<std::size_t>(n) == sizeof buffer) return false;
    const std::string_view path(buffer, static_cast<std::size_t>(n));
    if (path.compare(0, rootReal.size(), rootReal) != 0) return false;
    return path.size() == rootReal.size() || rootReal == "/" || path[rootReal.size()] == '/';
}

/// Opens the directory `relative` below `rootFd`: -1 with errno set, EXDEV when it leads out.
int openBeneath(int rootFd, const std::string& rootReal, const std::string& relative)
{
    constexpr int kFlags = O_PATH | O_DIRECTORY | O_CLOEXEC;
#ifdef SYS_openat2
    open_how how{};
    how.flags = kFlags;
    how.resolve = RESOLVE_BENEATH | RESOLVE_NO_MAGICLINKS;
    const long beneath = ::syscall(SYS_openat2, rootFd, relative.c_str(), &how, sizeof how);
    if (beneath >= 0) return static_cast<int>(beneath);
    // EXDEV also refuses an absolute link to a place inside the root, and ENOSYS or EPERM
    // come from a kernel or sandbox without openat2: the checked open below decides those.
    if (errno == ENOENT || errno == ENOTDIR || errno == ELOOP || errno == EACCES) return -1;
#endif
    const int fd = ::openat(rootFd, relative.c_str(), kFlags);
    if (fd < 0) return -1;
    if (!liesBeneath(fd, rootReal)) {
        ::close(fd);
        errno = EXDEV;
        return -1;
    }
    return fd;
}

/// Why `name` in the directory `parent` (`shown` in messages) could not be opened: `error`.
std::string describe(int error, int parent, const std::string& name, const std::string& shown)
{
    char target[PATH_MAX];
    const ssize_t n = ::readlinkat(parent, name.c_str(), target, sizeof target - 1);
    const std::string link = n > 0 ? std::string(target, static_cast<std::size_t>(n)) : "";
    if (error == EXDEV)
        return "'" + shown + "' leads outside the output directory" +
               (link.empty() ? "" : " (a symbolic link to '" + link + "')");
    if (error == ENOENT && !link.empty())
        return "'" + shown + "' is a symbolic link to '" + link + "', which does not exist";
    if (error == ENOTDIR) return "'" + shown + "' is not a directory";
    return "cannot open directory '" + shown + "': " + std::strerror(error);
}

std::string walk(const fs::path& root, const fs::path& file, bool create)
{
    if (create) {
        std::error_code ec;
        fs::create_directories(root, ec);
        if (ec) return "cannot create the output directory: " + ec.message();
    }
    const Fd rootFd(::open(root.empty() ? "." : root.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC));
    if (rootFd.get() < 0) {
        if (!create && errno == ENOENT) return "";  // nothing made yet: nothing in the way
        return std::string("cannot open the output directory: ") + std::strerror(errno);
    }
    char* real = ::realpath(root.empty() ? "." : root.c_str(), nullptr);
    if (!real) return std::string("cannot resolve the output directory: ") + std::strerror(errno);
    const std::string rootReal(real);
    std::free(real);

    Fd parent;  // the directory found last (none yet: the root)
    std::string prefix;
    for (const fs::path& component : file.parent_path()) {
        const std::string name = component.string();
        if (name.empty() || name == ".") continue;
        const int at = parent.get() >= 0 ? parent.get() : rootFd.get();
        prefix += (prefix.empty() ? "" : "/") + name;
        int fd = openBeneath(rootFd.get(), rootReal, prefix);
        if (fd < 0 && errno == ENOENT) {
            if (!create) return "";
            // Made in the directory found beneath the root, never through a path.
            if (::mkdirat(at, name.c_str(), 0777) != 0 && errno != EEXIST)
                return "cannot create directory '" + prefix + "': " + std::strerror(errno);
            fd = openBeneath(rootFd.get(), rootReal, prefix);
        }
        if (fd < 0) return describe(errno, at, name, prefix);
        parent = Fd(fd);
    }
    const int at = parent.get() >= 0 ? parent.get() : rootFd.get();
    struct stat st {};
    if (::fstatat(at, file.filename().c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 &&
        S_ISDIR(st.st_mode))
        return "'" + file.lexically_normal().string() + "' is a directory";
    return "";
}

}  // namespace

std::string makeOutputPlace(const fs::path& root, const fs::path& file)
{
    return walk(root, file, true);
}

std::string outputPlaceProblem(const fs::path& root, const fs::path& file)
{
    return walk(root, file, false);
}

}  // namespace cg::util
