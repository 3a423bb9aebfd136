#include "cli/PreviewPicture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>

#include "nodes/data/CloudParticles.h"
#include "nodes/data/Image.h"
#include "nodes/data/Map2D.h"
#include "nodes/data/VapourParticles.h"

namespace cg::cli {

namespace {

struct Extent {
    float minX = std::numeric_limits<float>::infinity();
    float maxX = -std::numeric_limits<float>::infinity();
    float minZ = std::numeric_limits<float>::infinity();
    float maxZ = -std::numeric_limits<float>::infinity();

    void add(float x, float z)
    {
        if (!std::isfinite(x) || !std::isfinite(z)) return;
        minX = std::min(minX, x);
        maxX = std::max(maxX, x);
        minZ = std::min(minZ, z);
        maxZ = std::max(maxZ, z);
    }
    void add(const Extent& e)
    {
        add(e.minX, e.minZ);
        add(e.maxX, e.maxZ);
    }
};

/// Counts of points a pixel over a side view (x right, z up) of an extent, in two kinds
/// (0: cloud or condensed particles, 1: vapour).
class PointCounts {
public:
    explicit PointCounts(const Extent& extent)
    {
        const bool empty = !(extent.maxX >= extent.minX);
        mMinX = empty ? 0.f : extent.minX;
        mMinZ = empty ? 0.f : extent.minZ;
        const double spanX = empty ? 1.0 : std::max<double>(extent.maxX - extent.minX, 1.0);
        const double spanZ = empty ? 1.0 : std::max<double>(extent.maxZ - extent.minZ, 1.0);
        mWidth = kPointsPictureWidth;
        mHeight = static_cast<int>(std::clamp(std::ceil(mWidth * spanZ / spanX), 64.0, 640.0));
        mScale = std::min((mWidth - 1) / spanX, (mHeight - 1) / spanZ);
        for (auto& c : mCounts) c.assign(static_cast<std::size_t>(mWidth) * mHeight, 0);
    }

    /// The pixel a point falls on, or -1 when it falls outside.
    long pixelOf(float x, float z) const
    {
        if (!std::isfinite(x) || !std::isfinite(z)) return -1;
        const long px = std::lround((x - mMinX) * mScale);
        const long pz = std::lround((z - mMinZ) * mScale);
        if (px < 0 || pz < 0 || px >= mWidth || pz >= mHeight) return -1;
        return (mHeight - 1 - pz) * static_cast<long>(mWidth) + px;
    }
    void add(int kind, long pixel)
    {
        if (pixel >= 0) ++mCounts[kind][static_cast<std::size_t>(pixel)];
    }

    PreviewPicture picture() const
    {
        PreviewPicture p{mWidth, mHeight, {}};
        p.rgb.resize(static_cast<std::size_t>(mWidth) * mHeight * 3);
        std::uint32_t most = 1;
        for (const auto& c : mCounts)
            for (const std::uint32_t n : c) most = std::max(most, n);
        const double norm = 1.0 / std::log1p(static_cast<double>(most));
        // Dark ground; condensed (or any) particles white, vapour blue.
        constexpr std::array<double, 3> kGround = {29, 35, 48};
        constexpr std::array<std::array<double, 3>, 2> kInk = {{{255, 255, 255}, {110, 170, 255}}};
        for (std::size_t i = 0; i < static_cast<std::size_t>(mWidth) * mHeight; ++i) {
            std::array<double, 3> c = kGround;
            for (std::size_t k = 0; k < mCounts.size(); ++k) {
                if (!mCounts[k][i]) continue;
                const double a = 0.35 + 0.65 * std::log1p(mCounts[k][i]) * norm;
                for (int ch = 0; ch < 3; ++ch) c[ch] = c[ch] * (1 - a) + kInk[k][ch] * a;
            }
            for (int ch = 0; ch < 3; ++ch) p.rgb[3 * i + ch] = static_cast<std::uint8_t>(c[ch]);
        }
        return p;
    }

private:
    int mWidth = 0, mHeight = 0;
    float mMinX = 0, mMinZ = 0;
    double mScale = 1;
    std::array<std::vector<std::uint32_t>, 2> mCounts;
};

PreviewPicture vapourPicture(const VapourParticlesData& particles,
                             const std::vector<std::int32_t>* condensedFrame)
{
    const std::vector<float>& xs = particles.xs();
    Extent extent;
    for (std::size_t i = 0; i < particles.size(); ++i) extent.add(xs[i], particles.z[i]);
    PointCounts counts(extent);
    for (std::size_t i = 0; i < particles.size(); ++i) {
        const bool vapour = condensedFrame && (*condensedFrame)[i] < 0;
        counts.add(vapour ? 1 : 0, counts.pixelOf(xs[i], particles.z[i]));
    }
    return counts.picture();
}

/// Two passes over the frame's chunks (its extent, then the points), so a streamed frame
/// is made twice rather than held whole.
PreviewPicture cloudPicture(const CloudParticlesData& cloud)
{
    std::mutex mutex;
    Extent extent;
    cloud.forEachChunk(
        [&](const algo::CloudChunk& chunk) {
            Extent local;
            for (std::uint64_t i = 0; i < chunk.count; ++i)
                local.add(chunk.positions[3 * i], chunk.positions[3 * i + 2]);
            std::lock_guard<std::mutex> lock(mutex);
            extent.add(local);
        },
        {});
    PointCounts counts(extent);
    cloud.forEachChunk(
        [&](const algo::CloudChunk& chunk) {
            std::vector<long> pixels(chunk.count);
            for (std::uint64_t i = 0; i < chunk.count; ++i)
                pixels[i] = counts.pixelOf(chunk.positions[3 * i], chunk.positions[3 * i + 2]);
            std::lock_guard<std::mutex> lock(mutex);  // sums of integers: any order
            for (const long pixel : pixels) counts.add(0, pixel);
        },
        {});
    return counts.picture();
}

PreviewPicture mapPicture(const Map2DData& map)
{
    PreviewPicture p{map.nx, map.ny, {}};
    p.rgb.resize(static_cast<std::size_t>(map.nx) * map.ny * 3);
    for (int iy = 0; iy < map.ny; ++iy)
        for (int ix = 0; ix < map.nx; ++ix) {
            const float v = std::clamp(map.at(ix, iy), 0.f, 1.f);
            const auto grey = static_cast<std::uint8_t>(std::lround(255.f * v));
            const std::size_t at = (static_cast<std::size_t>(map.ny - 1 - iy) * map.nx + ix) * 3;
            p.rgb[at] = p.rgb[at + 1] = p.rgb[at + 2] = grey;
        }
    return p;
}

}  // namespace

std::optional<PreviewPicture> previewPicture(const DataPtr& value,
                                             const algo::DisplaySettings& display)
{
    const Data* data = value.get();
    if (const auto* image = dynamic_cast<const ImageData*>(data))
        return PreviewPicture{image->width, image->height,
                              algo::displayRgb8(image->rgba, image->width, image->height, display)};
    if (const auto* map = dynamic_cast<const Map2DData*>(data)) return mapPicture(*map);
    if (const auto* vapour = dynamic_cast<const VapourParticlesData*>(data))
        return vapourPicture(*vapour, nullptr);
    if (const auto* condensation = dynamic_cast<const CondensationData*>(data))
        return vapourPicture(*condensation->particles, &condensation->condensedFrame);
    if (const auto* cloud = dynamic_cast<const CloudParticlesData*>(data))
        return cloudPicture(*cloud);
    return std::nullopt;
}

}  // namespace cg::cli
