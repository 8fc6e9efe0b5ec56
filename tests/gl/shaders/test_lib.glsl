// Included by shaders/test_pattern.frag.glsl for the GL tests (tests/gl/test_gl_*.cpp): a function
// whose body a define can change (TEST_LIB_SCALE), so a test can put an error inside an include.
#ifndef TEST_LIB_SCALE
#define TEST_LIB_SCALE 1.0
#endif
float test_lib_scale(float x) {
  return x * TEST_LIB_SCALE;
}
