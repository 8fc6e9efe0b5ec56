#include <gtest/gtest.h>
TEST(NoisePropsPlaceholder, Builds) {}
