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
/// Entries are written to tmp/ under a unique name, fsynced and renamed into objects/, so
/// readers (which only look in objects/) see no entry or a whole one. A temp file left by
/// a killed writer is never read.

#include "core/DiskCache.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <chrono>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <system_error>
#include <thread>

#include <spdlog/spdlog.h>

#include "core/Data.h"
#include "core/Error.h"
#include "core/Registry.h"

namespace cg {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'C', 'G', 'C', 'A', 'C', 'H', 'E', '1'};
constexpr std::uint32_t kVersion = 1;
constexpr std::size_t kHeaderSize = 56;
constexpr std::size_t kHeaderChecksumOffset = 48;
/// Larger files are not entries we wrote; refuse them before allocating.
constexpr std::uint64_t kMaxEntryBytes = 64ull << 30;

void putU32(unsigned char* p, std::uint32_t v)
{
    for (int i = 0; i < 4; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
void putU64(unsigned char* p, std::uint64_t v)
{
    for (int i = 0; i < 8; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
std::uint32_t getU32(const unsigned char* p)
{
    std::uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | p[i];
    return v;
}
std::uint64_t getU64(const unsigned char* p)
{
    std::uint64_t v = 0;
    for (int i = 7; i >= 0; --i) v = (v << 8) | p[i];
    return v;
}

[[noreturn]] void fail(std::size_t offset, const std::string& why)
{
    throw std::runtime_error("at byte " + std::to_string(offset) + ": " + why);
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

/// Reads a whole regular file; nullopt when it does not exist. Throws on other errors.
/// `identity` receives (device, inode) of what was read, so a damaged entry is only
/// removed if it is still the same file.
std::optional<std::vector<unsigned char>> readWholeFile(const fs::path& path,
                                                        std::pair<dev_t, ino_t>* identity)
{
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        if (errno == ENOENT || errno == ENOTDIR) return std::nullopt;
        throw std::runtime_error(std::string("cannot open: ") + std::strerror(errno));
    }
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};

    struct stat st {};
    if (::fstat(fd, &st) != 0)
        throw std::runtime_error(std::string("cannot stat: ") + std::strerror(errno));
    if (identity) *identity = {st.st_dev, st.st_ino};
    if (!S_ISREG(st.st_mode)) throw std::runtime_error("not a regular file");
    const auto size = static_cast<std::uint64_t>(st.st_size);
    if (size > kMaxEntryBytes)
        throw std::runtime_error("at byte 0: file of " + std::to_string(size) +
                                 " bytes is larger than any entry");

    std::vector<unsigned char> buf(static_cast<std::size_t>(size));
    std::size_t done = 0;
    while (done < buf.size()) {
        const ssize_t n = ::read(fd, buf.data() + done, buf.size() - done);
        if (n < 0) {
            if (errno == EINTR) continue;
            throw std::runtime_error(std::string("read failed: ") + std::strerror(errno));
        }
        if (n == 0) break;  // shrank while reading; the checks below catch it
        done += static_cast<std::size_t>(n);
    }
    buf.resize(done);
    return buf;
}

std::string tempName()
{
    static std::atomic<std::uint64_t> counter{0};
    const std::size_t tid = std::hash<std::thread::id>{}(std::this_thread::get_id());
    char name[96];
    std::snprintf(name, sizeof(name), "%ld-%zx-%llu.tmp", static_cast<long>(::getpid()), tid,
                  static_cast<unsigned long long>(counter.fetch_add(1)));
    return name;
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
    removeStaleTempFiles();
}

void DiskCache::removeStaleTempFiles() const
{
    // Writers killed mid-write leave temp files; none is ever read, but they take space.
    // A live writer finishes within seconds, so a day-old temp file is an orphan.
    const auto cutoff = fs::file_time_type::clock::now() - std::chrono::hours(24);
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(mRoot / "tmp", ec)) {
        std::error_code statError;
        const auto written = entry.last_write_time(statError);
        if (!statError && written < cutoff) fs::remove(entry.path(), statError);
    }
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

std::vector<unsigned char> DiskCache::encodeEntry(const Key& key, const OutputMap& outputs,
                                                  bool& serializable)
{
    serializable = false;
    ByteWriter out;
    std::vector<unsigned char>& buf = out.buffer();
    buf.resize(kHeaderSize);  // filled in once the payload is known

    out.u64(outputs.size());
    for (const auto& [name, value] : outputs) {
        if (!value) return {};
        out.str(name);
        out.str(value->typeName());
        // Length placeholder, patched after serializing in place (no extra copy).
        const std::size_t lengthAt = buf.size();
        out.u64(0);
        if (!value->serialize(out)) return {};
        putU64(buf.data() + lengthAt, buf.size() - lengthAt - 8);
    }

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
    serializable = true;
    return std::move(buf);
}

OutputMap DiskCache::decodeEntry(const Key& key, const unsigned char* data, std::size_t size,
                                 const Registry& registry)
{
    if (size < kHeaderSize)
        fail(size, "file of " + std::to_string(size) + " bytes is shorter than the header");
    if (std::memcmp(data, kMagic, 8) != 0) fail(0, "bad magic, not a cache entry");
    if (const std::uint32_t v = getU32(data + 8); v != kVersion)
        fail(8, "unsupported format version " + std::to_string(v));
    const Key stored{getU64(data + 16), getU64(data + 24)};
    if (stored != key) fail(16, "entry is for key " + stored.hex() + ", not " + key.hex());
    if (getU64(data + 48) != checksum64(data, kHeaderChecksumOffset))
        fail(kHeaderChecksumOffset, "header checksum mismatch");
    if (getU32(data + 12) != 0) fail(12, "reserved field is not zero");
    const std::uint64_t payloadSize = getU64(data + 32);
    if (payloadSize != size - kHeaderSize)
        fail(32, "payload length " + std::to_string(payloadSize) + " but " +
                     std::to_string(size - kHeaderSize) + " bytes follow the header");
    const unsigned char* payload = data + kHeaderSize;
    if (getU64(data + 40) != checksum64(payload, static_cast<std::size_t>(payloadSize)))
        fail(40, "payload checksum mismatch");

    PayloadCursor in(payload, static_cast<std::size_t>(payloadSize), kHeaderSize);
    const std::size_t countAt = in.offset();
    const std::uint64_t count = in.u64("port count");
    // Each port takes at least three u64 lengths: rejects absurd counts up front.
    if (count > in.remaining() / 24) fail(countAt, "port count " + std::to_string(count) +
                                                       " does not fit in the payload");
    OutputMap outputs;
    for (std::uint64_t i = 0; i < count; ++i) {
        const std::size_t portAt = in.offset();
        std::string name = in.str("port name");
        const std::size_t typeAt = in.offset();
        const std::string typeName = in.str("type name");
        const std::size_t lengthAt = in.offset();
        const std::uint64_t length = in.u64("data length");
        if (length > in.remaining()) fail(lengthAt, "data length runs past the end");

        const DataTypeInfo* info = registry.findDataType(typeName);
        if (!info || !info->deserialize) fail(typeAt, "unknown data type '" + typeName + "'");

        const std::size_t dataAt = in.offset();
        ByteReader reader(in.here(), static_cast<std::size_t>(length));
        DataPtr value;
        try {
            value = info->deserialize(reader);
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

std::optional<OutputMap> DiskCache::load(const Key& key, const Registry& registry) const
{
    const fs::path path = entryPath(key);
    std::pair<dev_t, ino_t> identity{};
    try {
        auto bytes = readWholeFile(path, &identity);
        if (!bytes) return std::nullopt;
        return decodeEntry(key, bytes->data(), bytes->size(), registry);
    } catch (const std::exception& e) {
        spdlog::warn("disk cache: damaged entry {}: {}; recooking", path.string(), e.what());
    }
    // Remove only the file we judged: another process may have just renamed a good entry
    // into place.
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && st.st_dev == identity.first &&
        st.st_ino == identity.second)
        ::unlink(path.c_str());
    return std::nullopt;
}

bool DiskCache::store(const Key& key, const OutputMap& outputs) const
{
    bool serializable = false;
    const std::vector<unsigned char> bytes = encodeEntry(key, outputs, serializable);
    if (!serializable) return false;
    return writeAtomically(entryPath(key), bytes.data(), bytes.size());
}

bool DiskCache::writeAtomically(const fs::path& target, const void* data,
                                std::size_t size) const
{
    const fs::path temp = mRoot / "tmp" / tempName();
    std::string why;
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) {
        spdlog::warn("disk cache: cannot create {}: {}", temp.string(), std::strerror(errno));
        return false;
    }
    const auto* p = static_cast<const unsigned char*>(data);
    std::size_t done = 0;
    while (done < size) {
        const ssize_t n = ::write(fd, p + done, size - done);
        if (n < 0) {
            if (errno == EINTR) continue;
            why = std::string("write failed: ") + std::strerror(errno);
            break;
        }
        done += static_cast<std::size_t>(n);
    }
    // The data must be on disk before the rename makes it visible, or a crash could leave
    // a whole-looking entry with garbage inside (the checksum would still catch it).
    if (why.empty() && ::fsync(fd) != 0) why = std::string("fsync failed: ") + std::strerror(errno);
    if (::close(fd) != 0 && why.empty())
        why = std::string("close failed: ") + std::strerror(errno);

    if (why.empty()) {
        std::error_code ec;
        fs::create_directories(target.parent_path(), ec);
        if (!ec) fs::rename(temp, target, ec);
        if (ec) why = "cannot move into place: " + ec.message();
    }
    if (why.empty()) return true;
    ::unlink(temp.c_str());
    spdlog::warn("disk cache: cannot write {}: {}", target.string(), why);
    return false;
}

std::optional<nlohmann::json> DiskCache::loadRecord(const std::string& name) const
{
    const fs::path path = mRoot / "records" / (sanitizeName(name) + ".json");
    std::optional<std::vector<unsigned char>> bytes;
    try {
        bytes = readWholeFile(path, nullptr);
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
    writeAtomically(path, text.data(), text.size());
}

}  // namespace cg
