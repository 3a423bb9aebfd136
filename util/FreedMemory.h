#pragma once
/// The allocator settings CloudGraph's programs run with (the CLI, the render benchmark).

namespace cg::util {

/// glibc gives every block above its mmap threshold back to the kernel when it is freed and
/// maps it anew on the next allocation, so the renderer's and the voxelizer's per-frame
/// buffers would be faulted in and zeroed by the kernel again every frame. Blocks up to
/// glibc's largest threshold come from the heap instead, and freed memory stays there for
/// the next frame, which renders faster (docs/benchmarks.md). Process-wide; elsewhere than
/// glibc, nothing happens.
void keepFreedMemoryForReuse();

}  // namespace cg::util
