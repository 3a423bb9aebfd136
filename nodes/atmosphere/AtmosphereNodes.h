#pragma once
/// The stochastic atmosphere of Sec. 5.1: environment, density map, vapour emission,
/// thermal rise and condensation.

namespace cg {

class Registry;

void registerAtmosphereNode(Registry& registry);          // Atmosphere
void registerNoiseMapNode(Registry& registry);            // NoiseMap
void registerThermalFieldNode(Registry& registry);        // ThermalField: power-law thermals
void registerMapMathNode(Registry& registry);             // MapMath
void registerVapourEmitterNode(Registry& registry);       // VapourEmitter
void registerThermalIntegratorNode(Registry& registry);   // ThermalIntegrator
void registerCondensationNode(Registry& registry);        // Condensation
void registerVapourPointsNode(Registry& registry);        // VapourPoints
void registerWriteWeatherReportNode(Registry& registry);  // WriteWeatherReport: JSON, CSV, skew-T

}  // namespace cg
