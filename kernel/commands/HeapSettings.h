#pragma once
// How a program that edits a document many times should keep its heap. Every edit recompiles
// the sculpture (and the studio relaxes after each), allocating and freeing arrays of hundreds of
// kilobytes to tens of megabytes; by default glibc returns such memory to the system and maps it
// afresh, so each of the studio's drag steps paid thousands of page faults (a 20,000-knot
// bar-length edit 2.3-4.1 ms instead of 1.1-1.2 ms), and `netsculpt run` of the installation's
// script (without relaxing) took 1.12-1.21 s instead of 0.88-0.99 s. The CLI, the studio and the
// benchmark of the studio's live path call this once at start.

namespace netsculpt {

/// Keeps freed memory for reuse: blocks below 32 MiB come from the heap, and the heap's top is
/// returned to the system only beyond 256 MiB free. Does nothing where the C library has no
/// such settings.
void keepFreedMemoryForReuse();

} // namespace netsculpt
