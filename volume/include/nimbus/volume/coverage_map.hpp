// A coverage (weather) map: a grey image stretched over an area that says where clouds form
// (0: no cloud, 1: as without a map), and optionally how tall they grow. The idea is the weather
// map of Schneider's Nubis clouds (Schneider 2015, "The real-time volumetric cloudscapes of
// Horizon Zero Dawn"; Schneider 2017, "Nubis"), also in Unreal's volumetric clouds and Terragen.
// Image row 0 is the north edge (the top of the picture), column 0 the west edge; x east, y north,
// metres. Values are sampled bilinearly between pixel centres.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

namespace nimbus::volume {

// Images larger than these are refused before any pixel is allocated.
inline constexpr int kMaxCoverageMapSide = 16384;
inline constexpr int64_t kMaxCoverageMapPixels = int64_t(64) << 20;

struct CoverageImage {
  int width = 0, height = 0;
  std::vector<float> value;  // row-major from the north-west corner, each in [0, 1]
  std::string source;        // the file, or "array", for messages
};

// A PNG (8 or 16 bit; grey, grey + alpha, RGB or RGBA): the red channel (the grey of a grey
// image), 0..max onto 0..1; alpha is ignored. The file is untrusted: a path that is not a regular
// file (refused before it is opened), an image larger than kMaxCoverageMapSide a side or
// kMaxCoverageMapPixels in all, or declaring more pixels than its bytes can hold (deflate's
// 1032:1) or than memory takes (all refused from its header, before decoding), or anything libpng
// cannot read is a std::runtime_error naming the file.
std::shared_ptr<const CoverageImage> read_coverage_png(const std::string& path);

// From values in memory (row-major, row 0 north): std::invalid_argument naming `where` unless
// every value is finite and in [0, 1] and the size within the limits above.
std::shared_ptr<const CoverageImage> coverage_from_values(std::vector<float> values, int width, int height,
                                                          const std::string& where);

// The image over the rectangle [lo, lo + size] (metres). Periodic: the image wraps at its edges
// (the sky without edges: the extent is the period); otherwise points beyond the extent take the
// value of the nearest edge pixel.
class CoverageMap {
 public:
  CoverageMap(std::shared_ptr<const CoverageImage> image, glm::dvec2 lo_m, glm::dvec2 size_m, bool periodic,
              bool sets_height);

  double at(glm::dvec2 xy_m) const;  // bilinear, in [0, 1]
  // The mean over a rectangle, from 256 x 256 samples (exactly 1 for a map of 1 everywhere).
  double mean_over(glm::dvec2 lo_m, glm::dvec2 size_m) const;
  bool sets_height() const { return sets_height_; }
  glm::dvec2 lo() const { return lo_; }
  glm::dvec2 size() const { return size_; }

 private:
  std::shared_ptr<const CoverageImage> image_;
  glm::dvec2 lo_, size_;
  bool periodic_, sets_height_;
};

}  // namespace nimbus::volume
