#pragma once
/// Borrowed views of node data for the node-free mapping algorithm.

#include <memory>
#include <vector>

#include "algo/mapping/Mapping.h"
#include "nodes/data/Map2D.h"
#include "nodes/data/PrimitiveSet.h"
#include "nodes/data/VapourParticles.h"

namespace cg {

inline algo::CondensationView condensationView(const CondensationData& c)
{
    algo::CondensationView v;
    v.x = c.particles->xs().data();
    v.y = c.particles->ys().data();
    v.z = c.particles->z.data();
    v.condensedFrame = c.condensedFrame.data();
    v.condensedZ = c.condensedHeight.data();
    v.vz = c.particles->vz.data();
    v.vx = c.particles->vxs().empty() ? nullptr : c.particles->vxs().data();
    v.vy = c.particles->vys().empty() ? nullptr : c.particles->vys().data();
    v.count = c.particles->size();
    return v;
}

inline algo::MapView mapView(const Map2DData& m)
{
    return {m.values.data(), m.nx, m.ny, m.cellSize};
}

/// Keeps the per-frame pointer table alive with the view.
struct PrimitiveViewHolder {
    explicit PrimitiveViewHolder(const PrimitiveSetData& p)
    {
        for (int s = 0; s < p.frames(); ++s) frames.push_back(p.frame(s));
        view.counts = p.counts.data();
        view.frames = frames.data();
        view.frameCount = p.frames();
        view.frameTime = p.frameTime;
    }
    PrimitiveViewHolder(const PrimitiveViewHolder&) = delete;
    PrimitiveViewHolder& operator=(const PrimitiveViewHolder&) = delete;

    std::vector<const float*> frames;
    algo::PrimitiveView view;
};

/// The primitive sets a mapping node is given, in port order: 'primitive', then
/// 'primitive2' .. 'primitive4' where connected.
using PrimitiveInputs = std::vector<std::shared_ptr<const PrimitiveSetData>>;

/// Views of a library of primitives, their frame tables kept alive with them.
struct PrimitiveLibraryHolder {
    explicit PrimitiveLibraryHolder(const PrimitiveInputs& primitives)
        : library(views(primitives, holders))
    {
    }
    std::vector<std::unique_ptr<PrimitiveViewHolder>> holders;
    algo::PrimitiveLibrary library;

private:
    static std::vector<algo::PrimitiveView> views(
        const PrimitiveInputs& primitives,
        std::vector<std::unique_ptr<PrimitiveViewHolder>>& holders)
    {
        std::vector<algo::PrimitiveView> out;
        for (const auto& p : primitives) {
            holders.push_back(std::make_unique<PrimitiveViewHolder>(*p));
            out.push_back(holders.back()->view);
        }
        return out;
    }
};

}  // namespace cg
