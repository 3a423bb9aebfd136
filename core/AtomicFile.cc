#include "core/AtomicFile.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>

namespace cg {

namespace {
std::atomic<unsigned> gCounter{0};

void fsyncFile(const std::filesystem::path& p)
{
    const int fd = ::open(p.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return;
    ::fsync(fd);
    ::close(fd);
}
}  // namespace

AtomicOutput::AtomicOutput(std::filesystem::path target) : mTarget(std::move(target))
{
    mTemp = mTarget.parent_path() / ("." + mTarget.filename().string() + ".tmp." +
                                     std::to_string(::getpid()) + "." +
                                     std::to_string(gCounter.fetch_add(1)));
}

AtomicOutput::~AtomicOutput()
{
    if (!mCommitted) {
        std::error_code ec;
        std::filesystem::remove(mTemp, ec);
    }
}

void AtomicOutput::commit()
{
    fsyncFile(mTemp);
    std::error_code ec;
    std::filesystem::rename(mTemp, mTarget, ec);
    if (ec) throw std::runtime_error("cannot write '" + mTarget.string() + "': " + ec.message());
    mCommitted = true;
}

void writeFileAtomically(const std::filesystem::path& target, std::string_view bytes)
{
    AtomicOutput out(target);
    {
        std::ofstream f(out.tempPath(), std::ios::binary | std::ios::trunc);
        f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        f.close();
        if (!f) {
            throw std::runtime_error("cannot write '" + target.string() +
                                     "': " + std::strerror(errno));
        }
    }
    out.commit();
}

}  // namespace cg
