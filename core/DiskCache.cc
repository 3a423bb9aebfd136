/// Disk cache entry file format (version 1), all integers little-endian:
///
///   offset  size  field
///        0     8  magic "CGCACHE1"
///        8     4  u32 format version (1)
///       12     4  u32 reserved, 0
///       16     8  key hi
///       24     8  key lo
///       32     8  payload length (bytes after the header)
///       40     8  payload checksum: checksum64 of the payload
///       48     8  header checksum: checksum64 of bytes 0..47
///       56        payload:
///                   u64 port count, then per port (in name order):
///                   str port name, str data type name (str = u64 length + bytes),
///                   u64 data length, data bytes (Data::serialize through ByteWriter)
///
/// Entries are written to tmp/ under a unique name and renamed into objects/ (by
/// util::AtomicOutput), so readers (which only look in objects/) see no entry or a whole one;
/// they are not fsynced: an entry torn by an operating-system crash fails its checksums and
/// reads as a miss. A
/// temp file left by a killed writer is never read, and removed when the cache is next opened.

#include "core/DiskCache.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include <spdlog/spdlog.h>

#include "core/Data.h"
#include "core/Error.h"
#include "core/Registry.h"
#include "util/AtomicFile.h"
#include "util/LittleEndian.h"
#include "util/SystemMemory.h"

namespace cg {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'C', 'G', 'C', 'A', 'C', 'H', 'E', '1'};
constexpr std::uint32_t kVersion = 1;
constexpr std::size_t kHeaderSize = 56;
constexpr std::size_t kHeaderChecksumOffset = 48;
/// Larger files are not entries we wrote; refuse them before allocating.
constexpr std::uint64_t kMaxEntryBytes = 64ull << 30;
/// Records are small JSON explanations; a larger file is not one of ours.
constexpr std::uint64_t kMaxRecordBytes = 16ull << 20;
constexpr std::size_t kKeptBufferBytes = std::size_t(64) << 20;  ///< see store()

using util::getU32;
using util::getU64;
using util::putU32;
using util::putU64;

/// Bytes that are not a valid entry: it is removed and recooked. Other failures (I/O, out
/// of memory) leave the entry alone, as it may well be valid.
class DamagedEntry : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

[[noreturn]] void fail(std::size_t offset, const std::string& why)
{
    throw DamagedEntry("at byte " + std::to_string(offset) + ": " + why);
}

/// The most bytes one entry may take in memory now: half of what is available, so that a
/// large entry is a miss to recook rather than a machine driven into swap.
std::uint64_t loadableBytes()
{
    const std::uint64_t available = util::availableMemoryBytes();
    return available == 0 ? kMaxEntryBytes : std::min(kMaxEntryBytes, available / 2);
}

/// Checks the header (the first kHeaderSize bytes of a file of `fileSize` bytes) and
/// returns the payload length.
std::uint64_t checkHeader(const Key& key, const unsigned char* data, std::uint64_t fileSize)
{
    if (fileSize < kHeaderSize)
        fail(fileSize, "file of " + std::to_string(fileSize) + " bytes is shorter than the header");
    if (std::memcmp(data, kMagic, 8) != 0) fail(0, "bad magic, not a cache entry");
    if (const std::uint32_t v = getU32(data + 8); v != kVersion)
        fail(8, "unsupported format version " + std::to_string(v));
    const Key stored{getU64(data + 16), getU64(data + 24)};
    if (stored != key) fail(16, "entry is for key " + stored.hex() + ", not " + key.hex());
    if (getU64(data + 48) != checksum64(data, kHeaderChecksumOffset))
        fail(kHeaderChecksumOffset, "header checksum mismatch");
    if (getU32(data + 12) != 0) fail(12, "reserved field is not zero");
    const std::uint64_t payloadSize = getU64(data + 32);
    if (payloadSize != fileSize - kHeaderSize)
        fail(32, "payload length " + std::to_string(payloadSize) + " but " +
                     std::to_string(fileSize - kHeaderSize) + " bytes follow the header");
    return payloadSize;
}

/// Walks the payload; every read checks bounds and reports absolute file offsets.
class PayloadCursor {
public:
    PayloadCursor(const unsigned char* data, std::size_t size, std::size_t base)
        : mData(data), mSize(size), mBase(base)
    {
    }
    std::size_t offset() const { return mBase + mPos; }
    std::size_t remaining() const { return mSize - mPos; }
    const unsigned char* here() const { return mData + mPos; }

    std::uint64_t u64(const char* what)
    {
        if (remaining() < 8) fail(offset(), std::string("file ends inside ") + what);
        const std::uint64_t v = getU64(here());
        mPos += 8;
        return v;
    }
    std::string str(const char* what)
    {
        const std::size_t at = offset();
        const std::uint64_t n = u64(what);
        if (n > remaining()) fail(at, std::string(what) + " length runs past the end");
        std::string s(reinterpret_cast<const char*>(here()), static_cast<std::size_t>(n));
        mPos += static_cast<std::size_t>(n);
        return s;
    }
    void skip(std::size_t n) { mPos += n; }

private:
    const unsigned char* mData;
    std::size_t mSize;
    std::size_t mBase;
    std::size_t mPos = 0;
};

std::string sanitizeName(const std::string& name)
{
    std::string out = name;
    for (char& c : out) {
        const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') ||
                        (c >= '0' && c <= '9') || c == '_' || c == '.' || c == '-';
        if (!ok) c = '_';
    }
    if (out.empty()) out = "_";
    return out;
}

/// An open file descriptor, closed on scope exit; moves, never copies.
struct FileHandle {
    int fd = -1;
    explicit FileHandle(int fd_) : fd(fd_) {}
    FileHandle(FileHandle&& other) noexcept : fd(other.fd) { other.fd = -1; }
    FileHandle(const FileHandle&) = delete;
    FileHandle& operator=(const FileHandle&) = delete;
    FileHandle& operator=(FileHandle&&) = delete;
    ~FileHandle()
    {
        if (fd >= 0) ::close(fd);
    }
};

/// Reads exactly `size` bytes at `offset`; throws std::runtime_error (not DamagedEntry: the
/// bytes were not judged) on an I/O error, DamagedEntry when the file ends early.
void readAt(int fd, unsigned char* out, std::size_t size, std::uint64_t offset)
{
    std::size_t done = 0;
    while (done < size) {
        const ssize_t n = ::pread(fd, out + done, size - done, static_cast<off_t>(offset + done));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw std::runtime_error(std::string("read failed: ") + std::strerror(errno));
        if (n == 0) fail(offset + done, "file shrank while being read");
        done += static_cast<std::size_t>(n);
    }
}

/// Opens a regular file for reading: nullopt when it does not exist. `st` receives what was
/// opened (device and inode), so a damaged entry is only removed if it is still that file.
std::optional<FileHandle> openRegular(const fs::path& path, struct stat& st)
{
    // O_NONBLOCK: opening a FIFO planted at an entry's path must not hang.
    FileHandle file{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
    if (file.fd < 0) {
        if (errno == ENOENT || errno == ENOTDIR) return std::nullopt;
        throw std::runtime_error(std::string("cannot open: ") + std::strerror(errno));
    }
    if (::fstat(file.fd, &st) != 0)
        throw std::runtime_error(std::string("cannot stat: ") + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) fail(0, "not a regular file");
    return file;
}

/// A small regular file (a record), whole; nullopt when absent or larger than `limit`.
std::optional<std::vector<unsigned char>> readSmallFile(const fs::path& path, std::uint64_t limit)
{
    struct stat st {};
    auto file = openRegular(path, st);
    if (!file || static_cast<std::uint64_t>(st.st_size) > limit) return std::nullopt;
    std::vector<unsigned char> bytes(static_cast<std::size_t>(st.st_size));
    readAt(file->fd, bytes.data(), bytes.size(), 0);
    return bytes;
}

}  // namespace

DiskCache::DiskCache(fs::path root) : mRoot(std::move(root))
{
    for (const fs::path& dir : {mRoot, mRoot / "objects", mRoot / "tmp", mRoot / "records"}) {
        std::error_code ec;
        fs::create_directories(dir, ec);
        if (ec || !fs::is_directory(dir, ec))
            throw InputError(mRoot.string(), "cannot create cache directory: " +
                                                 (ec ? ec.message() : dir.string()));
    }
    if (::access((mRoot / "tmp").c_str(), W_OK | X_OK) != 0)
        throw InputError(mRoot.string(),
                         std::string("cannot write cache directory: ") + std::strerror(errno));
    util::removeOrphanedTemporaries(mRoot / "tmp");
}

fs::path DiskCache::entryPath(const Key& key) const
{
    const std::string hex = key.hex();
    return mRoot / "objects" / hex.substr(0, 2) / (hex + ".cgc");
}

bool DiskCache::contains(const Key& key) const
{
    std::error_code ec;
    return fs::is_regular_file(entryPath(key), ec);
}

bool DiskCache::encodeEntry(const Key& key, const OutputMap& outputs,
                            std::vector<unsigned char>& buffer)
{
    buffer.clear();
    ByteWriter out(std::move(buffer));
    std::vector<unsigned char>& buf = out.buffer();
    buf.resize(kHeaderSize);  // filled in once the payload is known

    out.u64(outputs.size());
    bool serializable = true;
    for (const auto& [name, value] : outputs) {
        if (!value) {
            serializable = false;
            break;
        }
        out.str(name);
        out.str(value->typeName());
        // Length placeholder, patched after serializing in place (no extra copy).
        const std::size_t lengthAt = buf.size();
        out.u64(0);
        if (!value->serialize(out)) {
            serializable = false;
            break;
        }
        putU64(buf.data() + lengthAt, buf.size() - lengthAt - 8);
    }
    if (serializable) {
        const std::size_t payloadSize = buf.size() - kHeaderSize;
        unsigned char* h = buf.data();
        std::memcpy(h, kMagic, 8);
        putU32(h + 8, kVersion);
        putU32(h + 12, 0);
        putU64(h + 16, key.hi);
        putU64(h + 24, key.lo);
        putU64(h + 32, payloadSize);
        putU64(h + 40, checksum64(buf.data() + kHeaderSize, payloadSize));
        putU64(h + 48, checksum64(h, kHeaderChecksumOffset));
    }
    buffer = std::move(buf);
    return serializable;
}

OutputMap DiskCache::decodeEntry(const Key& key, const unsigned char* data, std::size_t size,
                                 const Registry& registry, const std::vector<PortDecl>* outputs)
{
    const std::uint64_t payloadSize = checkHeader(key, data, size);
    return decodePayload(data + kHeaderSize, static_cast<std::size_t>(payloadSize),
                         getU64(data + 40), registry, outputs);
}

OutputMap DiskCache::decodePayload(const unsigned char* payload, std::size_t payloadSize,
                                   std::uint64_t checksum, const Registry& registry,
                                   const std::vector<PortDecl>* declared)
{
    if (checksum != checksum64(payload, payloadSize)) fail(40, "payload checksum mismatch");

    PayloadCursor in(payload, static_cast<std::size_t>(payloadSize), kHeaderSize);
    const std::size_t countAt = in.offset();
    const std::uint64_t count = in.u64("port count");
    if (declared && count != declared->size())
        fail(countAt, std::to_string(count) + " ports stored, the node has " +
                          std::to_string(declared->size()));
    // Each port takes at least three u64 lengths: rejects absurd counts up front.
    if (count > in.remaining() / 24)
        fail(countAt, "port count " + std::to_string(count) + " does not fit in the payload");
    OutputMap outputs;
    for (std::uint64_t i = 0; i < count; ++i) {
        const std::size_t portAt = in.offset();
        std::string name = in.str("port name");
        const std::size_t typeAt = in.offset();
        const std::string typeName = in.str("type name");
        const std::size_t lengthAt = in.offset();
        const std::uint64_t length = in.u64("data length");
        if (length > in.remaining()) fail(lengthAt, "data length runs past the end");

        // Checked before anything is rebuilt: a value of the wrong type on a port would fail
        // (or worse) in the node that reads it, on every run.
        if (declared) {
            const auto port = std::find_if(declared->begin(), declared->end(),
                                           [&](const PortDecl& p) { return p.name == name; });
            if (port == declared->end()) fail(portAt, "the node has no output '" + name + "'");
            if (port->type != typeName)
                fail(typeAt, "output '" + name + "' holds a " + port->type + ", not a " + typeName);
        }
        const DataTypeInfo* info = registry.findDataType(typeName);
        if (!info || !info->deserialize) fail(typeAt, "unknown data type '" + typeName + "'");

        const std::size_t dataAt = in.offset();
        ByteReader reader(in.here(), static_cast<std::size_t>(length));
        DataPtr value;
        try {
            value = info->deserialize(reader);
        } catch (const std::bad_alloc&) {
            throw;  // not the entry's fault: it stays
        } catch (const std::exception& e) {
            fail(dataAt, "cannot rebuild '" + typeName + "' value: " + e.what());
        }
        if (!value) fail(dataAt, "'" + typeName + "' value rebuilt as null");
        if (!reader.atEnd())
            fail(dataAt + static_cast<std::size_t>(length) - reader.remaining(),
                 "'" + typeName + "' value leaves " + std::to_string(reader.remaining()) +
                     " bytes unread");
        in.skip(static_cast<std::size_t>(length));
        if (!outputs.emplace(std::move(name), std::move(value)).second)
            fail(portAt, "duplicate port name");
    }
    if (in.remaining() != 0) fail(in.offset(), "trailing bytes after the last port");
    return outputs;
}

std::optional<OutputMap> DiskCache::load(const Key& key, const Registry& registry,
                                         const std::vector<PortDecl>* outputs) const
{
    const fs::path path = entryPath(key);
    struct stat st {};
    try {
        auto file = openRegular(path, st);
        if (!file) return std::nullopt;
        // The header first: a damaged or foreign file is refused before its size is trusted.
        const auto fileSize = static_cast<std::uint64_t>(st.st_size);
        unsigned char header[kHeaderSize] = {};
        if (fileSize >= kHeaderSize) readAt(file->fd, header, kHeaderSize, 0);
        const std::uint64_t payloadSize = checkHeader(key, header, fileSize);
        if (payloadSize > loadableBytes()) {
            spdlog::warn(
                "disk cache: entry {} ({} bytes) does not fit in the memory available "
                "now; recooking",
                path.string(), payloadSize);
            return std::nullopt;
        }
        std::vector<unsigned char> payload(static_cast<std::size_t>(payloadSize));
        readAt(file->fd, payload.data(), payload.size(), kHeaderSize);
        OutputMap loaded =
            decodePayload(payload.data(), payload.size(), getU64(header + 40), registry, outputs);
        ::futimens(file->fd, nullptr);  // marks it recently used for pruneCache (best effort)
        return loaded;
    } catch (const DamagedEntry& e) {
        spdlog::warn("disk cache: damaged entry {}: {}; recooking", path.string(), e.what());
    } catch (const std::exception& e) {
        // I/O errors, out of memory: the entry may be valid, so it stays.
        spdlog::warn("disk cache: cannot read entry {}: {}; recooking", path.string(), e.what());
        return std::nullopt;
    }
    // Remove only the file we judged: another process may have just renamed a good entry
    // into place.
    struct stat now {};
    if (::stat(path.c_str(), &now) == 0 && now.st_dev == st.st_dev && now.st_ino == st.st_ino)
        ::unlink(path.c_str());
    return std::nullopt;
}

bool DiskCache::store(const Key& key, const OutputMap& outputs) const
{
    // One buffer per thread, kept between entries: a frame's entries are megabytes, and a
    // fresh buffer grown for each would be reallocated and page-faulted in every time, kernel
    // time that a cold run would spend on every entry. One larger than kKeptBufferBytes is
    // given back, so a thread does not hold a large volume's worth of memory for good.
    thread_local std::vector<unsigned char> bytes;
    // Entries carry checksums that load() verifies: one torn by an operating-system crash
    // reads as a miss, so the write need not wait for the disk.
    const bool stored = encodeEntry(key, outputs, bytes) &&
                        writeAtomically(entryPath(key), bytes.data(), bytes.size(),
                                        util::AtomicOutput::Flush::None);
    if (bytes.capacity() > kKeptBufferBytes) std::vector<unsigned char>().swap(bytes);
    return stored;
}

bool DiskCache::writeAtomically(const fs::path& target, const void* data, std::size_t size,
                                util::AtomicOutput::Flush flush) const
{
    try {
        std::error_code ec;
        fs::create_directories(target.parent_path(), ec);
        util::writeFileAtomically(target, std::string_view(static_cast<const char*>(data), size),
                                  mRoot / "tmp", flush);
        return true;
    } catch (const std::exception& e) {
        spdlog::warn("disk cache: {}", e.what());
        return false;
    }
}

std::optional<nlohmann::json> DiskCache::loadRecord(const std::string& name) const
{
    const fs::path path = mRoot / "records" / (sanitizeName(name) + ".json");
    std::optional<std::vector<unsigned char>> bytes;
    try {
        bytes = readSmallFile(path, kMaxRecordBytes);
    } catch (const std::exception& e) {
        spdlog::warn("disk cache: cannot read record {}: {}", path.string(), e.what());
        return std::nullopt;
    }
    if (!bytes) return std::nullopt;
    nlohmann::json record = nlohmann::json::parse(bytes->begin(), bytes->end(), nullptr,
                                                  /*allow_exceptions=*/false);
    if (record.is_discarded()) return std::nullopt;
    return record;
}

void DiskCache::storeRecord(const std::string& name, const nlohmann::json& record) const
{
    const fs::path path = mRoot / "records" / (sanitizeName(name) + ".json");
    // Replace bad UTF-8 rather than throw: a record is informational.
    const std::string text =
        record.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
    writeAtomically(path, text.data(), text.size(), util::AtomicOutput::Flush::ToDisk);
}

}  // namespace cg
