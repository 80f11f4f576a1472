// Giving freed heap memory back to the system between the phases of a long run.
#pragma once

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace mapfuse {

/// @brief Returns the free pages of every malloc arena to the system (glibc's malloc_trim; a
/// no-op elsewhere). Memory freed by worker threads stays in their arenas, where the main
/// thread's later allocations cannot reuse it: calling this after a parallel phase whose data
/// is gone keeps the process's peak RSS that of its largest phase, not the sum.
inline void releaseFreeHeap() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace mapfuse
