#include "formats/VdbFile.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <new>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <istream>
#include <memory>
#include <streambuf>

#include <openvdb/io/Stream.h>
#include <openvdb/io/io.h>
#include <openvdb/tree/LeafManager.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "formats/FormatError.h"
#include "util/InputFile.h"

namespace cg::formats {

namespace {

using G = openvdb::GridBase;

/// Runs `read` (OpenVDB calls on the file), turning what OpenVDB throws on bytes it cannot
/// read, std::bad_alloc included, into a FormatError naming the file and grid.
template <typename Fn>
auto guarded(const std::filesystem::path& path, const std::string& what, Fn&& read)
{
    try {
        return read();
    } catch (const FormatError&) {
        throw;
    } catch (const std::bad_alloc&) {
        // The sizes this file records were checked against the limit before OpenVDB read it,
        // so an allocation that fails now was asked for by a damaged size inside the grid's
        // data (OpenVDB allocates a compressed block's stated size before reading it).
        throw FormatError(path.string(), what +
                                             ": the file is damaged: a size inside the "
                                             "grid's data asks for more memory than there is");
    } catch (const std::exception& e) {
        throw FormatError(path.string(), what +
                                             ": the file is damaged, truncated or not a VDB "
                                             "file (OpenVDB: " +
                                             e.what() + ")");
    }
}

std::string gridWhat(const std::string& gridName) { return "grid '" + gridName + "'"; }

constexpr std::int64_t kVdbMagic = 0x56444220;
constexpr std::uint32_t kOldestVersion = 221;  // the oldest OpenVDB 10 reads
constexpr std::uint32_t kNewestVersion = 224;
constexpr std::uint32_t kNodeMaskCompression = 222;
const char kHalfSuffix[] = "_HalfFloat";

[[noreturn]] void refuse(const std::filesystem::path& path, const std::string& what,
                         const std::string& message)
{
    throw FormatError(path.string(), what + ": " + message);
}

/// An open file descriptor, closed on scope exit.
struct Fd {
    int fd = -1;
    ~Fd()
    {
        if (fd >= 0) ::close(fd);
    }
};

/// The bytes OpenVDB reads for a value of a plain fixed-size metadata type (TypedMetadata's
/// readValue ignores the size the file states), or -1 where it reads the stated size
/// (strings, delayed-load tables, types it does not know).
long fixedMetadataSize(const std::string& type)
{
    static const char* const kFixed[] = {"bool",  "int32", "int64", "float", "double", "vec2i",
                                         "vec2s", "vec2d", "vec3i", "vec3s", "vec3d",  "vec4i",
                                         "vec4s", "vec4d", "mat4s", "mat4d"};
    for (const char* fixed : kFixed)
        if (type == fixed && openvdb::Metadata::isRegisteredType(type))
            return static_cast<long>(openvdb::Metadata::createMetadata(type)->size());
    return -1;
}

/// Bounds-checked little-endian reads at a position of the file: every length the file
/// states is checked against the bytes left before anything is allocated for it.
class Cursor {
public:
    Cursor(const std::filesystem::path& path, const std::string& what, int fd, std::uint64_t pos,
           std::uint64_t end)
        : mPath(path), mWhat(what), mFd(fd), mPos(pos), mEnd(end)
    {
    }
    std::uint64_t pos() const { return mPos; }
    void seek(std::uint64_t pos) { mPos = pos; }
    std::uint64_t left() const { return mEnd - mPos; }
    std::string bytes(std::uint64_t n, const char* field)
    {
        if (n > left())
            refuse(mPath, mWhat,
                   "the file is truncated or damaged: " + std::string(field) + " at byte " +
                       std::to_string(mPos) + " needs " + std::to_string(n) + " bytes, " +
                       std::to_string(left()) + " are left");
        std::string out(static_cast<std::size_t>(n), '\0');
        std::size_t done = 0;
        while (done < out.size()) {
            const ssize_t r =
                ::pread(mFd, out.data() + done, out.size() - done, static_cast<off_t>(mPos + done));
            if (r <= 0)
                refuse(mPath, mWhat, "cannot read the file at byte " + std::to_string(mPos));
            done += static_cast<std::size_t>(r);
        }
        mPos += n;
        return out;
    }
    std::uint64_t uint(int size, const char* field)
    {
        const std::string b = bytes(static_cast<std::uint64_t>(size), field);
        std::uint64_t v = 0;
        for (int k = size - 1; k >= 0; --k) v = v << 8 | static_cast<unsigned char>(b[k]);
        return v;
    }
    std::uint32_t u32(const char* field) { return static_cast<std::uint32_t>(uint(4, field)); }
    std::int64_t i64(const char* field) { return static_cast<std::int64_t>(uint(8, field)); }
    std::string str(const char* field) { return bytes(u32(field), field); }
    void skip(std::uint64_t n, const char* field) { bytes(n, field); }

    /// A metadata table (MetaMap): a count, then name, type name, value size and value.
    void skipMetadata()
    {
        const std::uint32_t count = u32("metadata count");
        if (count > left() / 12)
            refuse(mPath, mWhat, "the file is damaged: metadata count " + std::to_string(count));
        for (std::uint32_t k = 0; k < count; ++k) {
            const std::string name = str("metadata name");
            const std::string type = str("metadata type");
            const std::uint32_t size = u32("metadata size");
            // OpenVDB reads a registered fixed-size value whatever size the file states; a
            // different size would put its reading out of step with this check.
            const long fixed = fixedMetadataSize(type);
            if (fixed >= 0 && size != static_cast<std::uint64_t>(fixed))
                refuse(mPath, mWhat,
                       "the file is damaged: metadata '" + name + "' of type " + type + " states " +
                           std::to_string(size) + " bytes");
            skip(size, "metadata value");
        }
    }

private:
    const std::filesystem::path& mPath;
    const std::string& mWhat;
    int mFd;
    std::uint64_t mPos, mEnd;
};

/// Where a grid lies in the file, from its descriptor.
struct Descriptor {
    std::string uniqueName;  ///< "name", or "name\x1eN" for the N-th grid of that name
    std::string type;        ///< "Tree_float_5_4_3", without the half-float suffix
    bool half = false;
    bool instance = false;  ///< shares the tree of another grid
    std::uint64_t start = 0, gridPos = 0, blockPos = 0, endPos = 0;

    std::string name() const { return uniqueName.substr(0, uniqueName.find('\x1e')); }
    /// OpenVDB's "name[N]" form for every grid after the first of a name.
    std::string displayName() const
    {
        const auto sep = uniqueName.find('\x1e');
        return sep == std::string::npos
                   ? uniqueName
                   : uniqueName.substr(0, sep) + "[" + uniqueName.substr(sep + 1) + "]";
    }
    /// "float", "double", "vec3s", ... from "Tree_<value>_5_4_3".
    std::string valueType() const
    {
        std::string v = type;
        if (v.rfind("Tree_", 0) == 0) v = v.substr(5);
        const auto tail = v.find('_');
        return tail == std::string::npos ? v : v.substr(0, tail);
    }
};

/// The file's header and grid descriptors, checked against its size: what OpenVDB's reader
/// would trust (string lengths, counts, offsets) is checked here first.
struct Layout {
    std::filesystem::path path;
    Fd fd;
    std::uint64_t size = 0;
    std::string header;  ///< the bytes up to the file's metadata
    std::uint32_t version = 0;
    openvdb::VersionId library;
    std::vector<Descriptor> grids;
};

std::unique_ptr<Layout> readLayout(const std::filesystem::path& path, const std::string& what,
                                   std::uint64_t maxBytes)
{
    if (const std::string problem = util::inputFileProblem(path, maxBytes); !problem.empty())
        refuse(path, what, "cannot read the VDB file: it " + problem);
    auto layout = std::make_unique<Layout>();
    layout->path = path;
    layout->fd.fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    struct stat st {};
    if (layout->fd.fd < 0 || ::fstat(layout->fd.fd, &st) != 0 || !S_ISREG(st.st_mode))
        refuse(path, what, "cannot open the VDB file");
    layout->size = static_cast<std::uint64_t>(st.st_size);
    Cursor in(path, what, layout->fd.fd, 0, layout->size);
    if (layout->size < 8 || in.i64("magic number") != kVdbMagic)
        refuse(path, what, "not a VDB file (no VDB magic number at its start)");
    layout->version = in.u32("file version");
    if (layout->version < kOldestVersion || layout->version > kNewestVersion)
        refuse(path, what,
               "VDB file format version " + std::to_string(layout->version) +
                   "; this build reads versions " + std::to_string(kOldestVersion) + " to " +
                   std::to_string(kNewestVersion));
    layout->library.first = in.u32("library version");
    layout->library.second = in.u32("library version");
    if (in.bytes(1, "grid offsets flag")[0] == 0)
        refuse(path, what, "written as a stream without grid offsets; save it as a file");
    if (layout->version < kNodeMaskCompression) in.skip(1, "compression flag");
    in.skip(36, "UUID");
    {
        Cursor all(path, what, layout->fd.fd, 0, in.pos());
        layout->header = all.bytes(in.pos(), "header");
    }
    in.skipMetadata();
    const std::uint32_t count = in.u32("grid count");
    if (count > in.left() / 36)  // three strings' lengths and three offsets at least
        refuse(path, what, "the file is damaged: grid count " + std::to_string(count));
    for (std::uint32_t k = 0; k < count; ++k) {
        Descriptor d;
        d.start = in.pos();
        d.uniqueName = in.str("grid name");
        d.type = in.str("grid type");
        const std::size_t suffix = sizeof kHalfSuffix - 1;
        if (d.type.size() > suffix &&
            d.type.compare(d.type.size() - suffix, suffix, kHalfSuffix) == 0) {
            d.half = true;
            d.type.resize(d.type.size() - suffix);
        }
        d.instance = !in.str("instance parent").empty();
        const std::int64_t grid = in.i64("grid offset"), block = in.i64("block offset"),
                           end = in.i64("end offset");
        // The grid follows its descriptor; its parts in order; the end inside the file.
        if (grid != static_cast<std::int64_t>(in.pos()) || block < grid || end < block ||
            static_cast<std::uint64_t>(end) > layout->size)
            refuse(path, what,
                   "the file is truncated or damaged: grid '" + d.displayName() +
                       "' claims bytes " + std::to_string(grid) + " to " + std::to_string(end) +
                       " of a file of " + std::to_string(layout->size));
        d.gridPos = static_cast<std::uint64_t>(grid);
        d.blockPos = static_cast<std::uint64_t>(block);
        d.endPos = static_cast<std::uint64_t>(end);
        in.seek(d.endPos);
        layout->grids.push_back(std::move(d));
    }
    return layout;
}

/// A read-only stream of `prefix` followed by the file's bytes [begin, end), for OpenVDB's
/// readers: it ends where the grid ends, and its owner makes reading past that end throw.
class RangeBuf final : public std::streambuf {
public:
    RangeBuf(int fd, std::string prefix, std::uint64_t begin, std::uint64_t end)
        : mFd(fd), mPrefix(std::move(prefix)), mNext(begin), mEnd(end), mBuffer(1 << 16)
    {
        char* p = mPrefix.data();
        setg(p, p, p + mPrefix.size());
    }

protected:
    int_type underflow() override
    {
        if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
        mConsumed += static_cast<std::uint64_t>(egptr() - eback());
        const std::uint64_t n = std::min<std::uint64_t>(mBuffer.size(), mEnd - mNext);
        if (n == 0) return traits_type::eof();
        const ssize_t r = ::pread(mFd, mBuffer.data(), n, static_cast<off_t>(mNext));
        if (r <= 0) return traits_type::eof();
        mNext += static_cast<std::uint64_t>(r);
        setg(mBuffer.data(), mBuffer.data(), mBuffer.data() + r);
        return traits_type::to_int_type(*gptr());
    }
    /// Only the current position can be asked for (OpenVDB's leaf reader does); no seeking.
    pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override
    {
        if (off != 0 || dir != std::ios_base::cur) return pos_type(off_type(-1));
        return pos_type(off_type(mConsumed + static_cast<std::uint64_t>(gptr() - eback())));
    }

private:
    int mFd;
    std::string mPrefix;
    std::uint64_t mNext, mEnd, mConsumed = 0;
    std::vector<char> mBuffer;
};

/// The grid named `gridName` (or "name[N]"), or nullptr.
const Descriptor* findGrid(const Layout& layout, const std::string& gridName)
{
    for (const Descriptor& d : layout.grids)
        if (d.displayName() == gridName) return &d;
    for (const Descriptor& d : layout.grids)
        if (d.name() == gridName) return &d;
    return nullptr;
}

/// The grid's metadata and transform, without its tree; with `background`, also the tree's
/// background value, which opens the tree's topology (a buffer count, then the root's
/// background as a full float or double, in every format version), so that a grid whose
/// background is not 0 is refused before its voxels are read.
openvdb::GridBase::Ptr readHeaderOf(const Layout& layout, const Descriptor& d,
                                    const std::string& what, double* background = nullptr)
{
    // The lengths OpenVDB trusts: the metadata's and the transform's map type name.
    Cursor check(layout.path, what, layout.fd.fd, d.gridPos, d.blockPos);
    if (layout.version >= kNodeMaskCompression) check.u32("compression");
    check.skipMetadata();
    check.str("transform type");

    return guarded(layout.path, what, [&] {
        RangeBuf buf(layout.fd.fd, "", d.gridPos, d.blockPos);
        std::istream is(&buf);
        is.exceptions(std::ios_base::failbit | std::ios_base::badbit);
        auto meta = std::make_shared<openvdb::io::StreamMetadata>();
        openvdb::io::setStreamMetadataPtr(is, meta, /*transfer=*/false);
        openvdb::io::setVersion(is, layout.library, layout.version);
        std::uint32_t compression = openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK;
        if (layout.version >= kNodeMaskCompression)
            is.read(reinterpret_cast<char*>(&compression), sizeof compression);
        openvdb::io::setDataCompression(is, compression);
        openvdb::GridBase::Ptr grid = openvdb::GridBase::createGrid(d.type);
        grid->setSaveFloatAsHalf(d.half);
        grid->readMeta(is);
        grid->removeMeta(G::META_FILE_DELAYED_LOAD);
        grid->readTransform(is);
        if (background) {
            std::int32_t buffers = 0;
            is.read(reinterpret_cast<char*>(&buffers), sizeof buffers);
            if (d.valueType() == "double") {
                is.read(reinterpret_cast<char*>(background), sizeof(double));
            } else {
                float value = 0.0f;
                is.read(reinterpret_cast<char*>(&value), sizeof value);
                *background = value;
            }
        }
        return grid;
    });
}

/// The whole grid, read by OpenVDB from a stream of the file's header and this grid alone.
openvdb::GridBase::Ptr readWhole(const Layout& layout, const Descriptor& d, const std::string& what)
{
    return guarded(layout.path, what, [&] {
        std::string prefix = layout.header;
        prefix.append(4, '\0');          // no file metadata
        prefix.append("\x01\0\0\0", 4);  // one grid
        RangeBuf buf(layout.fd.fd, std::move(prefix), d.start, d.endPos);
        std::istream is(&buf);
        is.exceptions(std::ios_base::failbit | std::ios_base::badbit);
        openvdb::io::Stream stream(is, /*delayLoad=*/false);
        const openvdb::GridPtrVecPtr grids = stream.getGrids();
        if (!grids || grids->size() != 1 || !(*grids)[0])
            refuse(layout.path, what, "OpenVDB read no grid");
        return (*grids)[0];
    });
}

std::uint64_t recorded(const openvdb::GridBase& grid, const char* name)
{
    if (const auto m = grid.getMetadata<openvdb::Int64Metadata>(name))
        return m->value() > 0 ? static_cast<std::uint64_t>(m->value()) : 0;
    return 0;
}

std::string bytesText(std::uint64_t bytes)
{
    char text[64];
    std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / double(1 << 20));
    return text;
}

/// The checks that need only the grid's metadata and transform.
void checkHeader(const std::filesystem::path& path, const std::string& what,
                 const openvdb::GridBase& grid, std::uint64_t maxBytes)
{
    const auto fail = [&](const std::string& message) {
        throw FormatError(path.string(), what + ": " + message);
    };
    const std::string type = grid.valueType();
    const openvdb::GridClass cls = grid.getGridClass();
    if (cls == openvdb::GRID_LEVEL_SET)
        fail(
            "is a level set (signed distances to a surface), not a fog volume of densities; "
            "convert it to a fog volume first (Houdini: VDB Convert, to Fog Volume; OpenVDB: "
            "tools::sdfToFogVolume)");
    if (cls != openvdb::GRID_FOG_VOLUME && cls != openvdb::GRID_UNKNOWN)
        fail("is of class '" + G::gridClassToString(cls) + "', not a fog volume");
    const openvdb::math::Transform& xf = grid.transform();
    if (!xf.isLinear())
        fail("has a non-linear transform (" + xf.mapType() +
             ", e.g. a frustum); the renderer needs a linear one");
    // Voxel sizes first: a scale map whose determinant underflows makes getAffineMap()
    // invert a singular matrix, and OpenVDB's exception from there ends the process.
    const openvdb::Vec3d voxel = xf.voxelSize();
    for (int a = 0; a < 3; ++a)
        if (!(voxel[a] >= 1e-6 && voxel[a] <= 1e9))
            fail("has voxels of " + std::to_string(voxel[a]) +
                 " (world units), outside 1e-6 to 1e9");
    const openvdb::Mat4d m = xf.baseMap()->getAffineMap()->getMat4();
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            if (!std::isfinite(m(r, c))) fail("has a transform that is not finite");

    // Sizes as the file records them, before a byte of the tree is read.
    const std::uint64_t voxels = recorded(grid, G::META_FILE_VOXEL_COUNT);
    const std::uint64_t memory = recorded(grid, G::META_FILE_MEM_BYTES);
    const std::uint64_t valueBytes = type == "double" ? 8 : 4;
    if (voxels > maxBytes / valueBytes)
        fail("has " + std::to_string(voxels) + " active voxels, more than the " +
             bytesText(maxBytes) + " this node may take can hold");
    if (memory > maxBytes)
        fail("takes " + bytesText(memory) + " of memory, more than the " + bytesText(maxBytes) +
             " this node may take");
}

std::string backgroundProblem(double background)
{
    return "has background " + std::to_string(background) +
           "; a fog volume's is 0 (a level set saved without its class has its band width)";
}

/// Sets negative values to 0 and finds a value that is not finite, leaf by leaf in parallel.
/// Returns a message naming the first such voxel in leaf order, or empty.
std::string cleanValues(openvdb::FloatGrid& grid)
{
    openvdb::tree::LeafManager<openvdb::FloatTree> leaves(grid.tree());
    constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
    std::atomic<std::size_t> firstBad{kNone};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.leafCount()),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i) {
                              float* v = leaves.leaf(i).buffer().data();
                              bool bad = false;
                              for (openvdb::Index k = 0; k < openvdb::FloatTree::LeafNodeType::SIZE;
                                   ++k) {
                                  if (!std::isfinite(v[k]))
                                      bad = true;
                                  else if (v[k] < 0.0f)
                                      v[k] = 0.0f;
                              }
                              if (!bad) continue;
                              std::size_t seen = firstBad.load();
                              while (i < seen && !firstBad.compare_exchange_weak(seen, i)) {
                              }
                          }
                      });
    const auto name = [](const openvdb::Coord& c, float v) {
        return "the value at voxel (" + std::to_string(c.x()) + ", " + std::to_string(c.y()) +
               ", " + std::to_string(c.z()) + ") is " + std::to_string(v) +
               "; densities must be finite";
    };
    if (firstBad != kNone) {
        const auto& leaf = leaves.leaf(firstBad);
        for (auto it = leaf.cbeginValueAll(); it; ++it)
            if (!std::isfinite(*it)) return name(it.getCoord(), *it);
    }
    // Tiles of the internal nodes and the root, without the leaves' voxels.
    auto it = grid.tree().beginValueAll();
    it.setMaxDepth(openvdb::FloatTree::ValueAllIter::LEAF_DEPTH - 1);
    for (; it; ++it) {
        if (!std::isfinite(*it)) return name(it.getCoord(), *it);
        if (*it < 0.0f) it.setValue(0.0f);
    }
    return "";
}

/// The metadata the rest of CloudGraph keeps for a fog volume: not the names OpenVDB gives a
/// meaning of its own, and only kinds the disk cache stores (FogVolumeCodec).
void keepPlainMetadata(openvdb::FloatGrid& grid)
{
    std::vector<std::string> drop;
    for (auto it = grid.beginMeta(); it != grid.endMeta(); ++it) {
        const std::string& name = it->first;
        if (name == G::META_GRID_NAME || name == G::META_GRID_CLASS) continue;
        const openvdb::Metadata& m = *it->second;
        const bool plain = dynamic_cast<const openvdb::BoolMetadata*>(&m) ||
                           dynamic_cast<const openvdb::Int32Metadata*>(&m) ||
                           dynamic_cast<const openvdb::Int64Metadata*>(&m) ||
                           dynamic_cast<const openvdb::FloatMetadata*>(&m) ||
                           dynamic_cast<const openvdb::DoubleMetadata*>(&m) ||
                           dynamic_cast<const openvdb::StringMetadata*>(&m);
        bool reserved = name.rfind("file_", 0) == 0;
        for (const char* owned : {G::META_GRID_CREATOR, G::META_SAVE_HALF_FLOAT,
                                  G::META_IS_LOCAL_SPACE, G::META_VECTOR_TYPE})
            reserved = reserved || name == owned;
        if (!plain || reserved) drop.push_back(name);
    }
    for (const std::string& name : drop) grid.removeMeta(name);
}

VdbGridSummary summaryOf(const Descriptor& d, const openvdb::GridBase& grid)
{
    VdbGridSummary s;
    s.name = d.displayName();
    s.valueType = d.valueType();
    s.gridClass = G::gridClassToString(grid.getGridClass());
    s.halfFloat = d.half;
    s.activeVoxels = recorded(grid, G::META_FILE_VOXEL_COUNT);
    s.memoryBytes = recorded(grid, G::META_FILE_MEM_BYTES);
    const auto lo = grid.getMetadata<openvdb::Vec3IMetadata>(G::META_FILE_BBOX_MIN);
    const auto hi = grid.getMetadata<openvdb::Vec3IMetadata>(G::META_FILE_BBOX_MAX);
    if (lo && hi) {
        const openvdb::Coord min(lo->value()), max(hi->value());
        // An empty grid is recorded with min > max: no box.
        if (min.x() <= max.x() && min.y() <= max.y() && min.z() <= max.z())
            s.activeBox = openvdb::CoordBBox(min, max);
    }
    return s;
}

}  // namespace

std::vector<VdbGridSummary> listVdbGrids(const std::filesystem::path& path, std::uint64_t maxBytes)
{
    openvdb::initialize();
    const auto layout = readLayout(path, "grids", maxBytes);
    std::vector<VdbGridSummary> grids;
    for (const Descriptor& d : layout->grids) {
        const std::string what = gridWhat(d.displayName());
        if (!openvdb::GridBase::isRegistered(d.type))
            refuse(path, what, "has type '" + d.type + "', which OpenVDB does not know");
        grids.push_back(summaryOf(d, *readHeaderOf(*layout, d, what)));
    }
    return grids;
}

namespace {

/// The layout, the grid's descriptor and its header, checked (see inspectVdbFogVolume).
struct Inspected {
    std::unique_ptr<Layout> layout;
    const Descriptor* grid = nullptr;
    openvdb::GridBase::Ptr header;
};

Inspected inspect(const std::filesystem::path& path, const std::string& gridName,
                  std::uint64_t maxBytes)
{
    openvdb::initialize();
    const std::string what = gridWhat(gridName);
    Inspected r;
    r.layout = readLayout(path, what, maxBytes);
    r.grid = findGrid(*r.layout, gridName);
    if (!r.grid) {
        std::string list;
        for (const Descriptor& d : r.layout->grids)
            list +=
                (list.empty() ? "" : ", ") + ("'" + d.displayName() + "' (" + d.valueType() + ")");
        refuse(path, what,
               "no such grid; " +
                   (list.empty() ? std::string("the file has no grids") : "its grids: " + list));
    }
    const std::string type = r.grid->valueType();
    if (type != "float" && type != "double")
        refuse(path, what,
               "holds " + type + " values; a fog volume is a grid of float (or double) densities");
    if (r.grid->instance)
        refuse(path, what, "is an instance sharing another grid's voxels; save it on its own");
    double background = 0.0;
    r.header = readHeaderOf(*r.layout, *r.grid, what, &background);
    // The same words as when the voxels are read: `validate` and `run` refuse alike.
    if (background != 0.0) refuse(path, what, backgroundProblem(background));
    // Guarded too: a forged matrix makes OpenVDB throw when asked for its affine map.
    guarded(path, what, [&] {
        checkHeader(path, what, *r.header, maxBytes);
        return 0;
    });
    return r;
}

}  // namespace

VdbGridSummary inspectVdbFogVolume(const std::filesystem::path& path, const std::string& gridName,
                                   std::uint64_t maxBytes)
{
    const Inspected r = inspect(path, gridName, maxBytes);
    return summaryOf(*r.grid, *r.header);
}

openvdb::FloatGrid::Ptr readVdbFogVolume(const std::filesystem::path& path,
                                         const std::string& gridName, std::uint64_t maxBytes)
{
    const std::string what = gridWhat(gridName);
    const Inspected r = inspect(path, gridName, maxBytes);
    const auto fail = [&](const std::string& message) { refuse(path, what, message); };
    const openvdb::GridBase::Ptr base = readWhole(*r.layout, *r.grid, what);
    // Guarded: OpenVDB throws on metadata of a forged type when it is touched.
    return guarded(path, what, [&] {
        openvdb::FloatGrid::Ptr grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
        if (!grid) {
            const auto doubles = openvdb::gridPtrCast<openvdb::DoubleGrid>(base);
            if (!doubles) fail("holds " + base->valueType() + " values, not float");
            // The tree's converting copy; a double beyond float's range becomes infinite and is
            // refused below.
            grid =
                openvdb::FloatGrid::create(std::make_shared<openvdb::FloatTree>(doubles->tree()));
            grid->setTransform(doubles->transform().copy());
            grid->insertMeta(*doubles);
        }
        if (grid->memUsage() > maxBytes)
            fail("takes " + bytesText(grid->memUsage()) + " of memory, more than the " +
                 bytesText(maxBytes) + " this node may take");
        if (grid->background() != 0.0f) fail(backgroundProblem(grid->background()));
        if (const std::string problem = cleanValues(*grid); !problem.empty()) fail(problem);
        // Removed first: a forged file can give "name" or "class" a type that refuses a string.
        grid->removeMeta(G::META_GRID_NAME);
        grid->removeMeta(G::META_GRID_CLASS);
        grid->setName("density");
        grid->setGridClass(openvdb::GRID_FOG_VOLUME);
        keepPlainMetadata(*grid);  // also "is_saved_as_half_float": full floats from here on
        return grid;
    });
}

}  // namespace cg::formats
