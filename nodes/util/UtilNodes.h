#pragma once
/// General-purpose nodes: sources, array arithmetic, a simple simulation, statistics and
/// writers. They carry the demo graph and exercise the engine end to end.

namespace cg {

class Registry;

void registerSourceNodes(Registry& registry);     // Constant, Oscillator, RandomField
void registerArrayNodes(Registry& registry);      // Scale, Sum
void registerIntegrateNode(Registry& registry);   // Integrate
void registerStatisticsNode(Registry& registry);  // Statistics
void registerWriterNodes(Registry& registry);     // WriteArray, WriteText
void registerLogTextNode(Registry& registry);     // LogText

}  // namespace cg
