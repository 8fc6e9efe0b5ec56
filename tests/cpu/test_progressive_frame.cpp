// A still view's progressive samples and their running mean (progressive_frame.hpp): the samples
// cover the pixel evenly and vary the jitter; the mean is the mean, and starts again for another
// state or size; a bad frame is refused and leaves the mean as it was.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "nimbus/render/sky/progressive_frame.hpp"

namespace nimbus::render {
namespace {

Image flat(int w, int h, float v) {
  Image im(w, h);
  for (float& x : im.rgba) x = v;
  return im;
}

TEST(ProgressiveFrame, SampleZeroIsThePlainFrame) {
  const ProgressiveSample s = progressive_sample(0);
  EXPECT_EQ(s.pixel_offset, glm::dvec2(0.0));
  EXPECT_EQ(s.jitter_frame, 0u);
}

TEST(ProgressiveFrame, SamplesCoverThePixelEvenlyAndVaryTheJitter) {
  // Any first n samples put about n / 16 in each of a 4x4 grid of sub-pixel cells: R2's
  // discrepancy. White noise would leave cells empty (at n = 64, P(some cell empty) ~ 0.26).
  for (const unsigned n : {32u, 64u, 256u}) {
    int cells[4][4] = {};
    std::set<unsigned> jitters;
    for (unsigned i = 1; i <= n; ++i) {
      const ProgressiveSample s = progressive_sample(i);
      ASSERT_GE(s.pixel_offset.x, -0.5);
      ASSERT_LT(s.pixel_offset.x, 0.5);
      ASSERT_GE(s.pixel_offset.y, -0.5);
      ASSERT_LT(s.pixel_offset.y, 0.5);
      ++cells[static_cast<int>((s.pixel_offset.x + 0.5) * 4)][static_cast<int>((s.pixel_offset.y + 0.5) * 4)];
      jitters.insert(s.jitter_frame);
    }
    EXPECT_EQ(jitters.size(), n) << "each sample its own jitter";
    const double expected = n / 16.0;
    for (const auto& row : cells)
      for (const int c : row) {
        EXPECT_GE(c, std::floor(0.5 * expected)) << n << " samples";
        EXPECT_LE(c, std::ceil(1.5 * expected)) << n << " samples";
      }
  }
}

TEST(ProgressiveFrame, TheMeanIsTheMeanOfTheFramesOfOneKey) {
  ProgressiveFrame p;
  EXPECT_EQ(p.samples(), 0u);
  p.add(flat(3, 2, 1.0f), "a");
  p.add(flat(3, 2, 2.0f), "a");
  const Image& m = p.add(flat(3, 2, 6.0f), "a");
  EXPECT_EQ(p.samples(), 3u);
  for (const float v : m.rgba) EXPECT_FLOAT_EQ(v, 3.0f);
  EXPECT_EQ(m.metadata.at("progressive_samples"), "3");
  // A long mean keeps its precision: 200000 frames of 0.1 still average 0.1 (a float sum would have drifted by percents).
  ProgressiveFrame q;
  Image tenth = flat(1, 1, 0.1f);
  for (int i = 0; i < 200000; ++i) q.add(tenth, "k");
  EXPECT_FLOAT_EQ(q.mean().rgba[0], 0.1f);
}

TEST(ProgressiveFrame, AnotherKeyOrSizeStartsAgain) {
  ProgressiveFrame p;
  p.add(flat(3, 2, 1.0f), "a");
  p.add(flat(3, 2, 5.0f), "b");
  EXPECT_EQ(p.samples(), 1u);
  EXPECT_FLOAT_EQ(p.mean().rgba[0], 5.0f);
  p.add(flat(4, 2, 7.0f), "b");
  EXPECT_EQ(p.samples(), 1u);
  EXPECT_EQ(p.mean().width, 4);
  EXPECT_FLOAT_EQ(p.mean().rgba[0], 7.0f);
  p.reset();
  EXPECT_EQ(p.samples(), 0u);
  EXPECT_EQ(p.mean().width, 0);
}

TEST(ProgressiveFrame, ABadFrameIsRefusedAndTheMeanKept) {
  ProgressiveFrame p;
  p.add(flat(2, 2, 1.0f), "a");
  for (const float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    Image f = flat(2, 2, 1.0f);
    f.rgba[5] = bad;
    try {
      p.add(f, "a");
      FAIL() << "a non-finite frame was taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("progressive frame"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(p.add(Image(), "a"), std::invalid_argument);
  EXPECT_EQ(p.samples(), 1u);
  for (const float v : p.mean().rgba) EXPECT_FLOAT_EQ(v, 1.0f);
}

TEST(ProgressiveFrame, BoxDownsampleAveragesEachBlock) {
  Image fine(4, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x)
      for (int c = 0; c < 4; ++c) fine.pixel(x, y)[c] = static_cast<float>(10 * x + y + c);
  const Image coarse = box_downsample(fine, 2);
  ASSERT_EQ(coarse.width, 2);
  ASSERT_EQ(coarse.height, 1);
  EXPECT_FLOAT_EQ(coarse.pixel(0, 0)[0], 5.5f);   // (0 + 10 + 1 + 11) / 4
  EXPECT_FLOAT_EQ(coarse.pixel(1, 0)[2], 27.5f);  // (20 + 30 + 21 + 31) / 4 + 2
  EXPECT_EQ(box_downsample(fine, 1).rgba, fine.rgba);
  EXPECT_THROW(box_downsample(fine, 3), std::invalid_argument);
  EXPECT_THROW(box_downsample(fine, 0), std::invalid_argument);
}

}  // namespace
}  // namespace nimbus::render
