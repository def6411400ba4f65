#pragma once
// How a long interactive session should keep its heap. Every edit of the studio recompiles the
// sculpture and runs a relaxation, allocating and freeing arrays of hundreds of kilobytes to tens
// of megabytes; by default glibc returns such memory to the system and maps it afresh, so each
// drag step paid thousands of page faults (a 20,000-knot bar-length edit 2.3-4.1 ms instead of
// 1.1-1.2 ms). The studio (and the benchmark of its live path) call this once at start.

namespace netsculpt {

/// Keeps freed memory for reuse: blocks below 32 MiB come from the heap, and the heap's top is
/// returned to the system only beyond 256 MiB free. Does nothing where the C library has no
/// such settings.
void keepFreedMemoryForReuse();

} // namespace netsculpt
