#pragma once
/// Writers of maps and particles, and the video encoder.

namespace cg {

class Registry;

void registerWriteMapNode(Registry& registry);        // WriteMap: PFM + 16-bit PNG preview
void registerReadMapNode(Registry& registry);         // ReadMap: PNG, PFM or EXR -> Map2D
void registerWriteParticlesNode(Registry& registry);  // WriteParticles: binary PLY
void registerEncodeVideoNode(Registry& registry);     // EncodeVideo: PNG frames -> MP4 (ffmpeg)
void registerRetimeNode(Registry& registry);          // Retime: a frame sequence at another rate

}  // namespace cg
