// Batched noise kernels, avx512 level (16 lane(s)); compiled with this level's flags.
#define NIMBUS_KERNEL_NS level_avx512
#define NIMBUS_WIDTH 16
#define NIMBUS_LEVEL_FN avx512
#include "batch_level.inl"
