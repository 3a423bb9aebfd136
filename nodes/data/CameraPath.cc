/// CameraPath's stored form, in ByteWriter's primitives (u64 little-endian, f64 a double's
/// bytes):
///
///   8 bytes  tag "CGCAMP02" (version 1, without the ease: refused)
///   u64      width, u64 height, each 1 to 2^20
///   u64      1 when the path eases at its ends, else 0
///   u64      key count, 1 to 2^20
///   f64 x 14 per key: frame, position, look-at, up (x, y, z each), vertical field of view
///            in degrees; checked as algo::checkCameraKeys checks them

#include "nodes/data/CameraPath.h"

#include <cstring>
#include <stdexcept>
#include <string>

#include "core/Registry.h"
#include "nodes/data/ValueChecks.h"

namespace cg {

namespace {

constexpr const char* kType = "CameraPath";
constexpr char kTag[8] = {'C', 'G', 'C', 'A', 'M', 'P', '0', '2'};
constexpr std::uint64_t kMaxSide = std::uint64_t{1} << 20;
constexpr std::uint64_t kMaxKeys = std::uint64_t{1} << 20;

algo::RenderVec3 readVector(ByteReader& in)
{
    const double x = in.f64(), y = in.f64(), z = in.f64();
    return {x, y, z};
}

void writeVector(ByteWriter& out, const algo::RenderVec3& v)
{
    for (int a = 0; a < 3; ++a) out.f64(v[a]);
}

DataPtr readCameraPath(ByteReader& in)
{
    char tag[8];
    in.bytes(tag, 8);
    if (std::memcmp(tag, kTag, 8) != 0) checks::refuse(kType, "no CGCAMP02 tag");
    const std::uint64_t w = in.u64(), h = in.u64(), ease = in.u64(), n = in.u64();
    if (ease > 1) checks::refuse(kType, "ease flag " + std::to_string(ease));
    if (w == 0 || h == 0 || w > kMaxSide || h > kMaxSide)
        checks::refuse(kType,
                       "size " + std::to_string(w) + " x " + std::to_string(h) + " is absurd");
    if (n == 0 || n > kMaxKeys) checks::refuse(kType, std::to_string(n) + " keys");
    std::vector<algo::CameraKey> keys(static_cast<std::size_t>(n));
    for (algo::CameraKey& k : keys) {
        k.frame = in.f64();
        k.position = readVector(in);
        k.lookAt = readVector(in);
        k.up = readVector(in);
        k.fovDegrees = in.f64();
    }
    try {
        algo::checkCameraKeys(keys);
    } catch (const std::invalid_argument& e) {
        checks::refuse(kType, e.what());
    }
    return std::make_shared<CameraPathData>(std::move(keys), static_cast<int>(w),
                                            static_cast<int>(h), ease == 1);
}

}  // namespace

CameraPathData::CameraPathData(std::vector<algo::CameraKey> keys_, int width_, int height_,
                               bool easeEnds_)
    : keys(std::move(keys_)), width(width_), height(height_), easeEnds(easeEnds_)
{
    algo::checkCameraKeys(keys);
    if (width < 1 || height < 1) throw std::invalid_argument("CameraPath: image size below 1");
}

algo::RenderCamera CameraPathData::at(double frame) const
{
    algo::RenderCamera base;
    base.width = width;
    base.height = height;
    return algo::cameraOnPath(keys, frame, base, easeEnds);
}

bool CameraPathData::serialize(ByteWriter& out) const
{
    out.bytes(kTag, 8);
    out.u64(static_cast<std::uint64_t>(width));
    out.u64(static_cast<std::uint64_t>(height));
    out.u64(easeEnds ? 1 : 0);
    out.u64(keys.size());
    for (const algo::CameraKey& k : keys) {
        out.f64(k.frame);
        writeVector(out, k.position);
        writeVector(out, k.lookAt);
        writeVector(out, k.up);
        out.f64(k.fovDegrees);
    }
    return true;
}

void registerCameraPathType(Registry& registry)
{
    registry.addDataType({kType,
                          "a camera over the whole shot: keys (frame, position, look-at, up, "
                          "vertical field of view) and the image size",
                          readCameraPath});
}

}  // namespace cg
