/// FogVolume's stored form, version 1, in ByteWriter's primitives (u64, f64 little-endian;
/// str = u64 length + bytes; f32 = a float's 4 bytes as podVector stores them):
///
///   8 bytes  tag "CGFOG001"
///   16 f64   the transform's 4x4 matrix, row by row, in OpenVDB's convention (points are row
///            vectors: rows 0-2 are the index axes in metres, row 3 the translation); finite,
///            affine (column 3 is 0, 0, 0, 1), each axis 1e-3 m to 1e6 m long, the axes
///            spanning at least 1e-3 of the cube their lengths make (non-singular), the
///            translation within 1e9 m
///   f32      background: 0 (a fog volume's)
///   u64      metadata count; per entry, names strictly increasing (not "name" or "class":
///            the grid is always "density", class fog volume; none of the other names OpenVDB
///            reserves, such as "file_compression", whose types its writer assumes):
///              str name, u64 kind, value: 1 bool (u64 0 or 1), 2 int32 (u64, two's
///              complement of the int64), 3 int64 (u64), 4 float (f32), 5 double (f64),
///              6 string (str)
///   u64      tile count; per tile, strictly increasing by (level, x, y, z):
///              u64 level 1, 2 or 3 (a tile of 8, 128 or 4096 voxels a side, held by the node
///              of that level), 3 u64 origin (two's complement, a multiple of the side),
///              f32 value, u64 active (0 or 1; an inactive tile is stored only when its value
///              is not the background)
///   u64      leaf count; per leaf, strictly increasing by origin (x, y, z):
///              3 u64 origin (a multiple of 8), 8 u64 value mask (bit i is voxel i in
///              OpenVDB's offset order, word 0 first), 512 f32 values (active or not)
///
/// Every value is finite and >= 0 (water volumes go above 1); every voxel a tile or leaf covers has
/// coordinates of magnitude below 2^30; no tile or leaf lies inside a tile of a higher level; the
/// internal nodes the tiles and leaves need take at most 256 MiB beyond 32 times the leaves' memory
/// (a few bytes of tile must not make megabytes of nodes). The decoder refuses anything
/// else, so a mutated entry is a miss to recook, never a crash or an absurd allocation; the
/// encoder refuses (returns false for) any grid the decoder would refuse.

#include "nodes/data/FogVolumeCodec.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "nodes/data/ValueChecks.h"

namespace cg {

namespace {

using Tree = openvdb::FloatTree;
using Internal2 = Tree::RootNodeType::ChildNodeType;
using Internal1 = Internal2::ChildNodeType;
using Leaf = Internal1::ChildNodeType;
using openvdb::Coord;

constexpr const char* kType = "FogVolume";
constexpr char kTag[8] = {'C', 'G', 'F', 'O', 'G', '0', '0', '1'};
constexpr std::int64_t kMaxCoord = std::int64_t{1} << 30;
// OpenVDB refuses maps with |det| < 3e-15: voxels of 1 mm and axes at least 1e-3 of a cube's
// volume keep clear of that.
constexpr double kMinVoxel = 1e-3, kMaxVoxel = 1e6, kMaxTranslation = 1e9, kMinVolumeRatio = 1e-3;
constexpr std::uint64_t kMaxNodeBytes = std::uint64_t{256} << 20;
constexpr std::uint64_t kWordsPerMask = Leaf::NodeMaskType::WORD_COUNT;
constexpr std::size_t kTileBytes = 8 + 3 * 8 + 4 + 8;
constexpr std::size_t kLeafBytes = 3 * 8 + kWordsPerMask * 8 + Leaf::SIZE * 4;
constexpr std::size_t kLeafMemory = sizeof(Leaf) + Leaf::SIZE * sizeof(float);  // with its buffer
constexpr std::size_t kMetaEntryBytes = 3 * 8;  // at least a name length, a kind, a value

enum MetaKind : std::uint64_t { kBool = 1, kInt32, kInt64, kFloat, kDouble, kString };

/// Side, in voxels, of a tile held by the node of `level` (1..3).
std::int64_t tileSide(std::uint64_t level)
{
    return level == 1 ? Leaf::DIM : level == 2 ? Internal1::DIM : Internal2::DIM;
}

Coord alignDown(const Coord& c, std::int64_t side)
{
    const auto mask = ~static_cast<openvdb::Int32>(side - 1);
    return Coord(c.x() & mask, c.y() & mask, c.z() & mask);
}

struct Tile {
    std::uint64_t level;
    Coord origin;
    float value;
    bool active;
    bool operator<(const Tile& o) const
    {
        return level != o.level ? level < o.level : origin < o.origin;
    }
};

// ---- checks shared by both directions: a problem, or nullopt -------------------------------

std::optional<std::string> matrixProblem(const openvdb::Mat4d& m)
{
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            if (!std::isfinite(m(r, c))) return "the transform is not finite";
    if (m(0, 3) != 0.0 || m(1, 3) != 0.0 || m(2, 3) != 0.0 || m(3, 3) != 1.0)
        return "the transform is not affine";
    double product = 1.0;
    for (int r = 0; r < 3; ++r) {
        const double axis = openvdb::Vec3d(m(r, 0), m(r, 1), m(r, 2)).length();
        if (!(axis >= kMinVoxel && axis <= kMaxVoxel))
            return "voxel axis " + std::to_string(r) + " is " + std::to_string(axis) + " m long";
        product *= axis;
        if (!(std::fabs(m(3, r)) <= kMaxTranslation)) return "the translation is out of range";
    }
    // Axes nearly in a plane make worldToIndex blow up: refuse a near-singular matrix.
    if (!(std::fabs(m.getMat3().det()) >= kMinVolumeRatio * product))
        return "the transform is singular";
    return std::nullopt;
}

/// A fog density (0..1) or, from the Voxelizer's water optics or a read VDB, any larger
/// finite value; NaN is not.
bool valueOk(float v) { return v >= 0.0f && std::isfinite(v); }

std::optional<std::string> valueProblem(float v)
{
    if (!valueOk(v)) return "value " + std::to_string(v) + " is negative or not finite";
    return std::nullopt;
}

/// The first of a leaf's values that is negative or not finite, or nullptr.
const float* firstBadValue(const float* values)
{
    const float* end = values + Leaf::SIZE;
    const float* bad = std::find_if_not(values, end, valueOk);
    return bad == end ? nullptr : bad;
}

/// Every voxel of the cube [origin, origin + side) within +-2^30, origin a multiple of side.
std::optional<std::string> cubeProblem(const Coord& origin, std::int64_t side)
{
    for (int a = 0; a < 3; ++a) {
        const std::int64_t lo = origin[a];
        if (lo % side != 0)
            return "origin " + std::to_string(lo) + " is not a multiple of " + std::to_string(side);
        if (lo <= -kMaxCoord || lo + side - 1 >= kMaxCoord)
            return "coordinate " + std::to_string(lo) + " is out of range";
    }
    return std::nullopt;
}

/// Bytes of the internal nodes that tiles and leaves at these origins need, over the budget.
std::optional<std::string> nodeBytesProblem(const std::vector<Tile>& tiles,
                                            const std::vector<Coord>& leaves)
{
    std::vector<Coord> ones, twos;  // origins of the level-1 and level-2 nodes needed
    for (const Tile& t : tiles) {
        if (t.level <= 1) ones.push_back(alignDown(t.origin, Internal1::DIM));
        if (t.level <= 2) twos.push_back(alignDown(t.origin, Internal2::DIM));
    }
    for (const Coord& c : leaves) {
        ones.push_back(alignDown(c, Internal1::DIM));
        twos.push_back(alignDown(c, Internal2::DIM));
    }
    for (auto* v : {&ones, &twos}) {
        std::sort(v->begin(), v->end());
        v->erase(std::unique(v->begin(), v->end()), v->end());
    }
    const std::uint64_t nodeBytes =
        ones.size() * sizeof(Internal1) + twos.size() * sizeof(Internal2);
    const std::uint64_t budget = kMaxNodeBytes + 32 * leaves.size() * kLeafMemory;
    if (nodeBytes > budget)
        return "its internal nodes would take " + std::to_string(nodeBytes) + " bytes, over " +
               std::to_string(budget);
    return std::nullopt;
}

/// "name" and "class": not stored, the decoder sets them.
bool identityMeta(const std::string& name)
{
    return name == openvdb::GridBase::META_GRID_NAME || name == openvdb::GridBase::META_GRID_CLASS;
}

/// Names OpenVDB gives a meaning (and a type) of its own when it writes or reads a grid: a
/// forged one could make a writer fail. No producer sets them.
bool openVdbMeta(const std::string& name)
{
    using G = openvdb::GridBase;
    for (const char* owned : {G::META_GRID_CREATOR, G::META_SAVE_HALF_FLOAT, G::META_IS_LOCAL_SPACE,
                              G::META_VECTOR_TYPE, G::META_FILE_BBOX_MIN, G::META_FILE_BBOX_MAX,
                              G::META_FILE_COMPRESSION, G::META_FILE_MEM_BYTES,
                              G::META_FILE_VOXEL_COUNT, G::META_FILE_DELAYED_LOAD})
        if (name == owned) return true;
    return false;
}

// ---- encoding ------------------------------------------------------------------------------

void putF32(ByteWriter& out, float v) { out.bytes(&v, sizeof v); }
void putCoord(ByteWriter& out, const Coord& c)
{
    for (int a = 0; a < 3; ++a) out.u64(static_cast<std::uint64_t>(std::int64_t{c[a]}));
}

bool encodeMeta(const openvdb::FloatGrid& grid, ByteWriter& out)
{
    std::size_t count = 0;
    for (auto it = grid.beginMeta(); it != grid.endMeta(); ++it) {
        if (openVdbMeta(it->first)) return false;
        count += !identityMeta(it->first);
    }
    out.u64(count);
    for (auto it = grid.beginMeta(); it != grid.endMeta(); ++it) {  // std::map: names in order
        if (identityMeta(it->first)) continue;
        const openvdb::Metadata& m = *it->second;
        out.str(it->first);
        if (const auto* b = dynamic_cast<const openvdb::BoolMetadata*>(&m)) {
            out.u64(kBool);
            out.u64(b->value() ? 1 : 0);
        } else if (const auto* i = dynamic_cast<const openvdb::Int32Metadata*>(&m)) {
            out.u64(kInt32);
            out.u64(static_cast<std::uint64_t>(std::int64_t{i->value()}));
        } else if (const auto* l = dynamic_cast<const openvdb::Int64Metadata*>(&m)) {
            out.u64(kInt64);
            out.u64(static_cast<std::uint64_t>(l->value()));
        } else if (const auto* f = dynamic_cast<const openvdb::FloatMetadata*>(&m)) {
            out.u64(kFloat);
            putF32(out, f->value());
        } else if (const auto* d = dynamic_cast<const openvdb::DoubleMetadata*>(&m)) {
            out.u64(kDouble);
            out.f64(d->value());
        } else if (const auto* s = dynamic_cast<const openvdb::StringMetadata*>(&m)) {
            out.u64(kString);
            out.str(s->value());
        } else {
            return false;  // a kind this format does not hold
        }
    }
    return true;
}

/// The stored tiles: active ones and inactive ones off the background, in stored order.
std::optional<std::vector<Tile>> collectTiles(const Tree& tree)
{
    std::vector<Tile> tiles;
    auto it = tree.cbeginValueAll();
    it.setMaxDepth(Tree::ValueAllCIter::LEAF_DEPTH - 1);  // tiles, not voxels
    for (; it; ++it) {
        const bool active = it.isValueOn();
        if (!active && *it == tree.background()) continue;
        const Tile t{it.getLevel(), it.getCoord(), *it, active};
        if (t.level < 1 || t.level > 3 || valueProblem(t.value) ||
            cubeProblem(t.origin, tileSide(t.level)))
            return std::nullopt;
        tiles.push_back(t);
    }
    std::sort(tiles.begin(), tiles.end());
    return tiles;
}

std::optional<std::vector<const Leaf*>> collectLeaves(const Tree& tree)
{
    std::vector<const Leaf*> leaves;
    for (auto it = tree.cbeginLeaf(); it; ++it) {
        const Leaf& leaf = *it;
        if (cubeProblem(leaf.origin(), Leaf::DIM) || firstBadValue(leaf.buffer().data()))
            return std::nullopt;
        leaves.push_back(&leaf);
    }
    std::sort(leaves.begin(), leaves.end(),
              [](const Leaf* a, const Leaf* b) { return a->origin() < b->origin(); });
    return leaves;
}

// ---- decoding ------------------------------------------------------------------------------

[[noreturn]] void refuse(const std::string& why) { checks::refuse(kType, why); }

float getF32(ByteReader& in)
{
    float v;
    in.bytes(&v, sizeof v);
    return v;
}

Coord getCoord(ByteReader& in)
{
    std::array<openvdb::Int32, 3> c{};
    for (int a = 0; a < 3; ++a)
        c[a] = static_cast<openvdb::Int32>(
            checks::intIn(in.u64(), -kMaxCoord, kMaxCoord, kType, "coordinate"));
    return Coord(c[0], c[1], c[2]);
}

/// A count of records of at least `recordBytes` each that must fit in what is left.
std::uint64_t getCount(ByteReader& in, std::size_t recordBytes, const char* what)
{
    const std::uint64_t n = in.u64();
    if (n > in.remaining() / recordBytes)
        refuse(std::string(what) + " count " + std::to_string(n) + " runs past the end");
    return n;
}

openvdb::math::Transform::Ptr decodeTransform(ByteReader& in)
{
    openvdb::Mat4d m;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) m(r, c) = in.f64();
    if (auto problem = matrixProblem(m)) refuse(*problem);
    try {
        return openvdb::math::Transform::createLinearTransform(m);
    } catch (const openvdb::Exception& e) {  // not expected after the checks above
        refuse(std::string("the transform: ") + e.what());
    }
}

void decodeMeta(ByteReader& in, openvdb::FloatGrid& grid)
{
    const std::uint64_t count = getCount(in, kMetaEntryBytes, "metadata");
    std::string previous;
    for (std::uint64_t k = 0; k < count; ++k) {
        std::string name = in.str();
        if (name.empty() || (k > 0 && name <= previous) || identityMeta(name) || openVdbMeta(name))
            refuse("metadata name '" + name + "' is empty, out of order or reserved");
        switch (in.u64()) {
            case kBool:
                grid.insertMeta(
                    name, openvdb::BoolMetadata(checks::uintUpTo(in.u64(), 1, kType, "bool") != 0));
                break;
            case kInt32:
                grid.insertMeta(name,
                                openvdb::Int32Metadata(static_cast<openvdb::Int32>(checks::intIn(
                                    in.u64(), std::numeric_limits<openvdb::Int32>::min(),
                                    std::numeric_limits<openvdb::Int32>::max(), kType, "int32"))));
                break;
            case kInt64:
                grid.insertMeta(name,
                                openvdb::Int64Metadata(static_cast<openvdb::Int64>(in.u64())));
                break;
            case kFloat:
                grid.insertMeta(name, openvdb::FloatMetadata(getF32(in)));
                break;
            case kDouble:
                grid.insertMeta(name, openvdb::DoubleMetadata(in.f64()));
                break;
            case kString:
                grid.insertMeta(name, openvdb::StringMetadata(in.str()));
                break;
            default:
                refuse("metadata '" + name + "' is of an unknown kind");
        }
        previous = std::move(name);
    }
}

std::vector<Tile> decodeTiles(ByteReader& in)
{
    const std::uint64_t count = getCount(in, kTileBytes, "tile");
    std::vector<Tile> tiles;
    tiles.reserve(static_cast<std::size_t>(count));
    for (std::uint64_t k = 0; k < count; ++k) {
        Tile t{};
        t.level = in.u64();
        if (t.level < 1 || t.level > 3)
            refuse("tile level " + std::to_string(t.level) + " is not 1, 2 or 3");
        t.origin = getCoord(in);
        t.value = getF32(in);
        t.active = checks::uintUpTo(in.u64(), 1, kType, "tile state") != 0;
        if (auto p = cubeProblem(t.origin, tileSide(t.level))) refuse("tile " + *p);
        if (auto p = valueProblem(t.value)) refuse("tile " + *p);
        if (!t.active && t.value == 0.0f) refuse("an inactive tile holds the background");
        if (!tiles.empty() && !(tiles.back() < t)) refuse("tiles are out of order or repeated");
        tiles.push_back(t);
    }
    return tiles;
}

/// Whether a cube at `origin` lies inside a stored tile of a level above `level`.
bool insideTile(const std::vector<Tile>& tiles, const Coord& origin, std::uint64_t level)
{
    for (std::uint64_t up = level + 1; up <= 3; ++up) {
        const Tile probe{up, alignDown(origin, tileSide(up)), 0.0f, false};
        if (std::binary_search(tiles.begin(), tiles.end(), probe)) return true;
    }
    return false;
}

std::vector<std::unique_ptr<Leaf>> decodeLeaves(ByteReader& in, const std::vector<Tile>& tiles)
{
    const std::uint64_t count = getCount(in, kLeafBytes, "leaf");
    std::vector<std::unique_ptr<Leaf>> leaves;
    leaves.reserve(static_cast<std::size_t>(count));
    for (std::uint64_t k = 0; k < count; ++k) {
        const Coord origin = getCoord(in);
        if (auto p = cubeProblem(origin, Leaf::DIM)) refuse("leaf " + *p);
        if (!leaves.empty() && !(leaves.back()->origin() < origin))
            refuse("leaves are out of order or repeated");
        if (insideTile(tiles, origin, 0)) refuse("a leaf lies inside a tile");
        Leaf::NodeMaskType mask;
        for (openvdb::Index w = 0; w < kWordsPerMask; ++w)
            mask.getWord<openvdb::Index64>(w) = in.u64();
        auto leaf = std::make_unique<Leaf>(origin, 0.0f);
        leaf->setValueMask(mask);
        float* values = leaf->buffer().data();
        in.bytes(values, Leaf::SIZE * sizeof(float));
        if (const float* bad = firstBadValue(values)) refuse("leaf " + *valueProblem(*bad));
        leaves.push_back(std::move(leaf));
    }
    return leaves;
}

}  // namespace

bool encodeFogVolume(const openvdb::FloatGrid& grid, ByteWriter& out)
{
    const openvdb::math::Transform& xform = grid.transform();
    if (grid.getName() != "density" || grid.getGridClass() != openvdb::GRID_FOG_VOLUME ||
        !xform.isLinear())
        return false;
    const openvdb::Mat4d matrix = xform.baseMap()->getAffineMap()->getMat4();
    const float background = grid.background();
    if (matrixProblem(matrix) || background != 0.0f || std::signbit(background)) return false;
    const auto tiles = collectTiles(grid.tree());
    const auto leaves = collectLeaves(grid.tree());
    if (!tiles || !leaves) return false;
    std::vector<Coord> origins;
    origins.reserve(leaves->size());
    for (const Leaf* leaf : *leaves) origins.push_back(leaf->origin());
    if (nodeBytesProblem(*tiles, origins)) return false;

    out.bytes(kTag, sizeof kTag);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) out.f64(matrix(r, c));
    putF32(out, background);
    if (!encodeMeta(grid, out)) return false;
    out.u64(tiles->size());
    for (const Tile& t : *tiles) {
        out.u64(t.level);
        putCoord(out, t.origin);
        putF32(out, t.value);
        out.u64(t.active ? 1 : 0);
    }
    out.u64(leaves->size());
    for (const Leaf* leaf : *leaves) {
        putCoord(out, leaf->origin());
        for (openvdb::Index w = 0; w < kWordsPerMask; ++w)
            out.u64(leaf->getValueMask().getWord<openvdb::Index64>(w));
        out.bytes(leaf->buffer().data(), Leaf::SIZE * sizeof(float));  // as f32 one by one
    }
    return true;
}

openvdb::FloatGrid::Ptr decodeFogVolume(ByteReader& in)
{
    char tag[sizeof kTag];
    in.bytes(tag, sizeof tag);
    if (std::memcmp(tag, kTag, sizeof tag) != 0) refuse("not a stored fog volume (bad tag)");
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setTransform(decodeTransform(in));
    const float background = getF32(in);
    if (background != 0.0f || std::signbit(background))
        refuse("background " + std::to_string(background) + " is not 0");
    decodeMeta(in, *grid);
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);

    const std::vector<Tile> tiles = decodeTiles(in);
    for (const Tile& t : tiles)
        if (insideTile(tiles, t.origin, t.level))
            refuse("a tile lies inside a tile of a higher level");
    std::vector<std::unique_ptr<Leaf>> leaves = decodeLeaves(in, tiles);
    std::vector<Coord> origins;
    origins.reserve(leaves.size());
    for (const auto& leaf : leaves) origins.push_back(leaf->origin());
    if (auto p = nodeBytesProblem(tiles, origins)) refuse(*p);

    Tree& tree = grid->tree();
    for (const Tile& t : tiles)
        tree.addTile(static_cast<openvdb::Index>(t.level), t.origin, t.value, t.active);
    for (auto& leaf : leaves) tree.addLeaf(leaf.release());  // the tree takes ownership
    return grid;
}

}  // namespace cg
