#include "util/InputFile.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace cg::util {

std::string inputFileProblem(const std::filesystem::path& path, std::uint64_t maxBytes)
{
    if (path.empty()) return "no file given";
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) return std::string("cannot open: ") + std::strerror(errno);
    struct stat st {};
    const bool statted = ::fstat(fd, &st) == 0;
    const int statError = errno;
    ::close(fd);
    if (!statted) return std::string("cannot stat: ") + std::strerror(statError);
    if (S_ISDIR(st.st_mode)) return "is a directory, not a file";
    if (!S_ISREG(st.st_mode)) return "is not a regular file (a device, FIFO or socket)";
    if (static_cast<std::uint64_t>(st.st_size) > maxBytes)
        return "is " + std::to_string(st.st_size) + " bytes, over the limit of " +
               std::to_string(maxBytes) + " bytes";
    return "";
}

}  // namespace cg::util
