#include "nodes/data/CloudSources.h"

#include <stdexcept>

#include "core/Registry.h"

namespace cg {

std::size_t CloudSourcesData::byteSize() const
{
    return sizeof(*this) + table.sources.size() * sizeof(algo::Source) +
           table.condensationTaken.size() + table.cloudTaken.size() * 8;
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
    }
    out.u64(static_cast<std::uint64_t>(table.topLevel));
    out.podVector(table.levelStart);
    out.podVector(table.condensationTaken);
    out.podVector(table.cloudTaken);
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
    return true;
}

void registerCloudSourcesType(Registry& registry)
{
    registry.addDataType({"CloudSources", "the mapper's table of source records (Sec. 5.2)",
                          [](ByteReader& in) -> DataPtr {
                              algo::SourceTable t;
                              const std::uint64_t n = in.u64();
                              if (n > in.remaining() / 56) throw std::runtime_error("CloudSources: bad count");
                              t.sources.resize(static_cast<std::size_t>(n));
                              for (algo::Source& src : t.sources) {
                                  src.level = static_cast<std::uint8_t>(in.u64());
                                  src.phase = static_cast<std::uint16_t>(in.u64());
                                  src.parent = static_cast<std::uint32_t>(in.u64());
                                  src.parentFluid = static_cast<std::uint32_t>(in.u64());
                                  src.startFrame = static_cast<std::int32_t>(static_cast<std::int64_t>(in.u64()));
                                  src.speed = static_cast<float>(in.f64());
                                  src.scale = static_cast<float>(in.f64());
                              }
                              t.topLevel = static_cast<std::int32_t>(in.u64());
                              t.levelStart = in.podVector<std::int32_t>();
                              t.condensationTaken = in.podVector<std::uint8_t>();
                              t.cloudTaken = in.podVector<std::uint64_t>();
                              algo::MappingSettings s;
                              s.maxLevel = static_cast<int>(in.u64());
                              s.selectionRatio = in.podVector<double>();
                              s.firstStart = static_cast<int>(static_cast<std::int64_t>(in.u64()));
                              s.levelDelay = static_cast<int>(in.u64());
                              s.windowLength = in.podVector<int>();
                              s.scaleCoefficient = in.f64();
                              s.speedCoefficient = in.f64();
                              s.metresPerPrimitiveMetre = in.f64();
                              s.timeStep = in.f64();
                              s.seed = in.u64();
                              s.maxSources = in.u64();
                              s.particlesPerCopy = static_cast<std::uint32_t>(in.u64());
                              for (std::size_t j = 0; j < t.sources.size(); ++j) {
                                  const algo::Source& src = t.sources[j];
                                  if (src.level == 0 || src.level > s.maxLevel ||
                                      (src.level > 1 && src.parent >= j))
                                      throw std::runtime_error("CloudSources: bad source record");
                              }
                              return std::make_shared<CloudSourcesData>(std::move(t), std::move(s));
                          }});
}

}  // namespace cg
