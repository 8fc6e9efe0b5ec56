// Batched noise kernels, sse41 level (4 lane(s)); compiled with this level's flags.
#define NIMBUS_KERNEL_NS level_sse41
#define NIMBUS_WIDTH 4
#define NIMBUS_LEVEL_FN sse41
#include "batch_level.inl"
