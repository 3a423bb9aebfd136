#include "nodes/data/CloudSources.h"

#include <limits>
#include <stdexcept>

#include "core/Registry.h"
#include "nodes/data/CloudParticles.h"
#include "nodes/data/ValueChecks.h"

namespace cg {

namespace {

constexpr const char* kType = "CloudSources";
constexpr std::size_t kStoredSourceBytes = 56;  // seven 8-byte fields
constexpr std::uint64_t kMaxU32 = std::numeric_limits<std::uint32_t>::max();

/// Reads one record; a field that does not fit its member is refused, not truncated.
algo::Source readSource(ByteReader& in)
{
    algo::Source src;
    src.level = static_cast<std::uint8_t>(checks::uintUpTo(in.u64(), 255, kType, "level"));
    src.phase = static_cast<std::uint16_t>(checks::uintUpTo(in.u64(), 65535, kType, "phase"));
    src.parent = static_cast<std::uint32_t>(checks::uintUpTo(in.u64(), kMaxU32, kType, "parent"));
    src.parentFluid =
        static_cast<std::uint32_t>(checks::uintUpTo(in.u64(), kMaxU32, kType, "parent fluid id"));
    src.startFrame = static_cast<std::int32_t>(
        checks::intIn(in.u64(), 0, checks::kMaxFrame, kType, "start frame"));
    const double inf = std::numeric_limits<double>::infinity();
    src.speed = checks::floatIn(in.f64(), -inf, inf, kType, "speed");
    src.scale = checks::floatIn(in.f64(), -inf, inf, kType, "scale");
    src.flatten = checks::floatIn(in.f64(), -inf, inf, kType, "flatten");
    return src;
}

algo::MappingSettings readSettings(ByteReader& in)
{
    using L = MappingLimits;
    algo::MappingSettings s;
    s.maxLevel = static_cast<int>(checks::intIn(in.u64(), 1, kMaxCloudLevel, kType, "maxLevel"));
    s.selectionRatio = in.podVector<double>();
    s.firstStart =
        static_cast<int>(checks::intIn(in.u64(), -1, L::kMaxFrames, kType, "firstStart"));
    s.levelDelay = static_cast<int>(checks::intIn(in.u64(), 0, L::kMaxFrames, kType, "levelDelay"));
    s.windowLength = in.podVector<int>();
    s.scaleCoefficient =
        checks::finiteIn(in.f64(), 0.0, L::kMaxCoefficient, kType, "scaleCoefficient");
    s.speedCoefficient =
        checks::finiteIn(in.f64(), 0.0, L::kMaxCoefficient, kType, "speedCoefficient");
    s.metresPerPrimitiveMetre =
        checks::finiteIn(in.f64(), L::kMinMetres, L::kMaxMetres, kType, "metresPerPrimitiveMetre");
    // Positive: the primitive time divides by nothing, but a zero step stops every copy.
    s.timeStep = checks::finiteIn(in.f64(), std::numeric_limits<double>::denorm_min(),
                                  L::kMaxTimeStep, kType, "time step");
    s.seed = in.u64();
    s.maxSources =
        static_cast<std::uint64_t>(checks::intIn(in.u64(), 1, L::kMaxSources, kType, "maxSources"));
    s.particlesPerCopy = static_cast<std::uint32_t>(
        checks::uintUpTo(in.u64(), L::kMaxParticlesPerCopy, kType, "particlesPerCopy"));
    s.parentRule =
        static_cast<algo::ParentRule>(checks::uintUpTo(in.u64(), 1, kType, "parentRule"));
    s.pastLastFrame =
        static_cast<algo::PastLastFrame>(checks::uintUpTo(in.u64(), 1, kType, "pastLastFrame"));
    s.level1Origin =
        static_cast<algo::Level1Origin>(checks::uintUpTo(in.u64(), 2, kType, "level1Origin"));
    s.trailRiseSpeed =
        checks::finiteIn(in.f64(), 0.0, L::kMaxTrailRiseSpeed, kType, "trailRiseSpeed");
    s.primitiveCount = static_cast<std::uint32_t>(
        checks::intIn(in.u64(), 1, algo::kMaxPrimitives, kType, "primitive count"));
    return s;
}

DataPtr readCloudSources(ByteReader& in)
{
    algo::SourceTable t;
    const std::uint64_t n = in.u64();
    if (n > in.remaining() / kStoredSourceBytes)
        checks::refuse(kType, "record count runs past the end");
    t.sources.resize(static_cast<std::size_t>(n));
    for (algo::Source& src : t.sources) src = readSource(in);
    t.topLevel =
        static_cast<std::int32_t>(checks::intIn(in.u64(), 1, kMaxCloudLevel, kType, "L_max"));
    t.levelStart = in.podVector<std::int32_t>();
    t.condensationTaken = in.podVector<std::uint8_t>();
    t.cloudTaken = in.podVector<std::uint64_t>();
    t.anchors = in.podVector<float>();
    algo::MappingSettings s = readSettings(in);
    checkSourceTable(t, s);
    return std::make_shared<CloudSourcesData>(std::move(t), std::move(s));
}

}  // namespace

std::size_t CloudSourcesData::byteSize() const
{
    return sizeof(*this) + table.sources.size() * sizeof(algo::Source) +
           table.condensationTaken.size() + table.cloudTaken.size() * 8 + table.anchors.size() * 4;
}

bool CloudSourcesData::serialize(ByteWriter& out) const
{
    // Field by field: the struct's padding bytes must not reach the disk cache.
    out.u64(table.sources.size());
    for (const algo::Source& src : table.sources) {
        out.u64(src.level);
        out.u64(src.phase);
        out.u64(src.parent);
        out.u64(src.parentFluid);
        out.u64(static_cast<std::uint64_t>(static_cast<std::int64_t>(src.startFrame)));
        out.f64(src.speed);
        out.f64(src.scale);
        out.f64(src.flatten);
    }
    out.u64(static_cast<std::uint64_t>(table.topLevel));
    out.podVector(table.levelStart);
    out.podVector(table.condensationTaken);
    out.podVector(table.cloudTaken);
    out.podVector(table.anchors);
    const algo::MappingSettings& s = settings;
    out.u64(static_cast<std::uint64_t>(s.maxLevel));
    out.podVector(s.selectionRatio);
    out.u64(static_cast<std::uint64_t>(static_cast<std::int64_t>(s.firstStart)));
    out.u64(static_cast<std::uint64_t>(s.levelDelay));
    out.podVector(s.windowLength);
    for (double v : {s.scaleCoefficient, s.speedCoefficient, s.metresPerPrimitiveMetre, s.timeStep})
        out.f64(v);
    out.u64(s.seed);
    out.u64(s.maxSources);
    out.u64(s.particlesPerCopy);
    for (auto choice :
         {static_cast<std::uint8_t>(s.parentRule), static_cast<std::uint8_t>(s.pastLastFrame),
          static_cast<std::uint8_t>(s.level1Origin)})
        out.u64(choice);
    out.f64(s.trailRiseSpeed);
    out.u64(s.primitiveCount);
    return true;
}

void registerCloudSourcesType(Registry& registry)
{
    registry.addDataType(
        {"CloudSources", "the mapper's table of source records (Sec. 5.2)", readCloudSources});
}

}  // namespace cg
