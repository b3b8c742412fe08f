// Every frame allocates its buffers anew (a 2048² shadow map's depth is 16 MB). glibc hands
// blocks that large to the kernel on free and maps fresh, zero pages for the next frame, which
// then fault in one 4 KB page at a time: several milliseconds a frame. Programs that render many
// frames (the CLI's bench, bench/) call this once at start so freed memory is kept for reuse.
#pragma once

namespace shadowref {

void keepFreedMemoryForReuse();

}  // namespace shadowref
