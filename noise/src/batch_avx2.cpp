// Batched noise kernels, avx2 level (8 lane(s)); compiled with this level's flags.
#define NIMBUS_KERNEL_NS level_avx2
#define NIMBUS_WIDTH 8
#define NIMBUS_LEVEL_FN avx2
#include "batch_level.inl"
