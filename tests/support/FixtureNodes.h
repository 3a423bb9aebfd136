#pragma once
/// Nodes for engine tests: they count their cooks, fail on purpose, or wait for
/// cancellation. Counts are per node id and reset with resetCookCounts().

#include <cstddef>
#include <string>

namespace cg {

class Registry;

/// Registers TestSource, TestAdd, TestSim, TestFail, TestWait, TestIntSource, TestTextSource,
/// and cheap sources of the domain types (TestPrimitiveSource, TestCloudSource,
/// TestFogSource, TestImageSource).
void registerFixtureNodes(Registry& registry);

std::size_t cookCount(const std::string& nodeId);
std::size_t totalCookCount();
void resetCookCounts();

/// A node type whose default output has the given port data type, for wiring any input.
/// Empty when there is none (the contract test then fails, asking for one).
std::string sourceNodeFor(const std::string& dataType, std::string& outputPort);

}  // namespace cg
