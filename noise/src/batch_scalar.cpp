// Batched noise kernels, scalar level (1 lane(s)); compiled with this level's flags.
#define NIMBUS_KERNEL_NS level_scalar
#define NIMBUS_WIDTH 1
#define NIMBUS_LEVEL_FN scalar
#include "batch_level.inl"
