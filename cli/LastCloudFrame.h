#pragma once
/// Where `serve`'s page opens: the last frame of the graph that has a cloud, so an artist
/// sees the cloud at once rather than an empty sky at frame 0.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>

#include "core/Graph.h"

namespace cg::cli {

/// The last frame in [start, end] at which `particlesAt` is not 0, sampling every `stride`
/// frames back from `end`, then every frame between the first hit and the sample after it.
/// A cloud that is gone at every sample is missed. nullopt when no sample has particles.
std::optional<int> lastFrameWithParticles(const std::function<std::size_t(int)>& particlesAt,
                                          int start, int end, int stride);

/// The node with a CloudParticles output that `node` depends on (itself included), the one
/// nearest it in topological order, and that output's port; nullopt when there is none.
std::optional<std::pair<std::string, std::string>> cloudSourceOf(const Graph& graph,
                                                                 const std::string& node);

}  // namespace cg::cli
