// Sparse generation of density grids, leaf block by leaf block.
#include "nimbus/volume/generate.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <glm/common.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "nimbus/base/cancel.hpp"
#include "nimbus/base/memory.hpp"

namespace nimbus::volume {
namespace {

using Leaf = openvdb::FloatTree::LeafNodeType;
constexpr int kLeaf = 8;  // Leaf::DIM

// A leaf block's far flags (CloudModel::densities) as bits, for a GenerationReuse.
constexpr size_t kFarWords = kLeaf * kLeaf * kLeaf / 64;
void pack_far(const uint8_t* far, uint64_t* words) {
  for (size_t w = 0; w < kFarWords; ++w) {
    uint64_t bits = 0;
    for (int b = 0; b < 64; ++b) bits |= uint64_t(far[w * 64 + b] != 0) << b;
    words[w] = bits;
  }
}
void unpack_far(const uint64_t* words, uint8_t* far) {
  for (size_t w = 0; w < kFarWords; ++w)
    for (int b = 0; b < 64; ++b) far[w * 64 + b] = uint8_t((words[w] >> b) & 1u);
}

int64_t floor_div(int64_t a, int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

int64_t to_index(double world, double voxel, bool up) {
  const double i = up ? std::ceil(world / voxel) : std::floor(world / voxel);
  if (!(std::fabs(i) < double(1 << 30)))
    throw std::invalid_argument("cloud bounds are too large for the voxel size (index beyond 2^30)");
  return static_cast<int64_t>(i);
}

// The voxels whose centres lie in the model's bounds; along a periodic axis exactly one period:
// the centres in [tile lo, tile lo + period), so that copies of the grid placed a period apart
// tile without a repeated or a missing voxel (when the period is a whole number of voxels).
void index_range(const CloudModel& model, double vs, const glm::dvec3& origin, int64_t lo[3], int64_t hi[3]) {
  const Aabb b = model.bounds();
  for (int a = 0; a < 3; ++a) {
    lo[a] = to_index(b.lo[a] + origin[a], vs, false);
    hi[a] = to_index(b.hi[a] + origin[a], vs, true);
  }
  if (const auto& t = model.tile())
    for (int a = 0; a < 2; ++a) {
      lo[a] = to_index(t->lo_m[a] + origin[a], vs, true);
      hi[a] = to_index(t->lo_m[a] + origin[a] + t->size_m[a], vs, true) - 1;
    }
}

}  // namespace

openvdb::CoordBBox density_index_box(const CloudParams& params, double voxel_size, double time,
                                      const glm::dvec3& origin_m) {
  int64_t lo[3], hi[3];
  index_range(CloudModel(params, voxel_size, time), voxel_size, origin_m, lo, hi);
  return {openvdb::Coord(int(lo[0]), int(lo[1]), int(lo[2])), openvdb::Coord(int(hi[0]), int(hi[1]), int(hi[2]))};
}

namespace {

// The grid's index box (a clip's, or the model's bounds, turned y-up when asked) and the leaf
// blocks that cover it.
struct BlockLayout {
  int64_t lo[3], hi[3];     // the index box, inclusive (hi < lo on an empty axis)
  int64_t voxels = 1;       // in the box
  int64_t blo[3], bn[3];    // first block and blocks per axis
  int64_t blocks = 0;
  openvdb::CoordBBox keep() const {
    return {openvdb::Coord{int(lo[0]), int(lo[1]), int(lo[2])}, openvdb::Coord{int(hi[0]), int(hi[1]), int(hi[2])}};
  }
  openvdb::Coord block_origin(int64_t id) const {
    const int64_t bx = blo[0] + id % bn[0], by = blo[1] + (id / bn[0]) % bn[1], bz = blo[2] + id / (bn[0] * bn[1]);
    return {int(bx * kLeaf), int(by * kLeaf), int(bz * kLeaf)};
  }
};

BlockLayout block_layout(const CloudModel& model, const GenerateOptions& o) {
  BlockLayout l;
  index_range(model, o.voxel_size, o.origin_m, l.lo, l.hi);
  if (o.y_up) {  // the same voxels turned: z-up (i, j, k) is y-up (i, k, -j)
    const int64_t jlo = l.lo[1], jhi = l.hi[1];
    l.lo[1] = l.lo[2];
    l.hi[1] = l.hi[2];
    l.lo[2] = -jhi;
    l.hi[2] = -jlo;
  }
  for (int a = 0; a < 3; ++a) {
    if (o.clip) {  // a sub-box: the same voxels as the whole grid has there
      l.lo[a] = std::max<int64_t>(l.lo[a], o.clip->min()[a]);
      l.hi[a] = std::min<int64_t>(l.hi[a], o.clip->max()[a]);
    }
    if (l.hi[a] < l.lo[a]) l.hi[a] = l.lo[a] - 1;  // nothing to do on this axis
    l.voxels *= l.hi[a] - l.lo[a] + 1;
    l.blo[a] = floor_div(l.lo[a], kLeaf);
    l.bn[a] = floor_div(l.hi[a], kLeaf) - l.blo[a] + 1;
  }
  l.blocks = l.voxels > 0 ? l.bn[0] * l.bn[1] * l.bn[2] : 0;
  return l;
}

// A GenerationReuse for one generation: read when its key is this generation's, else remade,
// and keyed only once whole.
class SavedTests {
 public:
  SavedTests(GenerationReuse* r, const CloudModel& model, const GenerateOptions& o, const BlockLayout& l) : r_(r) {
    if (!r_) return;
    key_ = {o.voxel_size, o.origin_m.x, o.origin_m.y, o.origin_m.z, double(o.y_up)};
    for (int a = 0; a < 3; ++a) key_.insert(key_.end(), {double(l.lo[a]), double(l.hi[a])});
    const std::vector<double> model_key = model.far_test_key();
    key_.insert(key_.end(), model_key.begin(), model_key.end());
    reading_ = r_->key == key_ && r_->touched.size() == size_t(l.blocks);
    if (!reading_) {
      r_->key.clear();  // set when the tests are whole: a generation stopped part-way saves none
      r_->touched.assign(size_t(l.blocks), 0);
      r_->far.assign(size_t(l.blocks) * kFarWords, 0);
    }
    r_->reused_blocks = 0;
  }
  bool saving() const { return r_ && !reading_; }
  bool reading() const { return reading_; }
  bool touched(int64_t id) const { return r_->touched[size_t(id)] != 0; }
  void set_touched(int64_t id) { r_->touched[size_t(id)] = 1; }
  const uint64_t* far(int64_t id) const { return &r_->far[size_t(id) * kFarWords]; }
  uint64_t* far(int64_t id) { return &r_->far[size_t(id) * kFarWords]; }
  void count_read() { reused_.fetch_add(1, std::memory_order_relaxed); }
  // After every block: the count read, and the key of tests now whole.
  void finish() {
    if (!r_) return;
    r_->reused_blocks = reused_.load();
    if (!reading_) r_->key = std::move(key_);
  }

 private:
  GenerationReuse* r_;
  std::vector<double> key_;
  bool reading_ = false;
  std::atomic<int64_t> reused_{0};
};

// The voxels of block `origin` with density >= kMinDensity inside `keep`, as a new leaf (null
// when none).
Leaf* leaf_of(const openvdb::Coord& origin, const float* d, const openvdb::CoordBBox& keep, GenerateStats& c) {
  Leaf* leaf = nullptr;
  for (int i = 0; i < kLeaf * kLeaf * kLeaf; ++i) {
    if (!(d[i] >= kMinDensity)) continue;
    // Only the index box (a clip's, or one period of a periodic field, whose density goes on
    // past it), though the leaf blocks reach beyond it.
    const openvdb::Coord ijk(origin.x() + i % kLeaf, origin.y() + (i / kLeaf) % kLeaf, origin.z() + i / (kLeaf * kLeaf));
    if (!keep.isInside(ijk)) continue;
    if (!leaf) leaf = new Leaf(origin, 0.0f, false);
    leaf->setValueOn(ijk, d[i]);
    ++c.active_voxels;
  }
  return leaf;
}

}  // namespace

openvdb::FloatGrid::Ptr generate_density(const CloudParams& params, const GenerateOptions& o,
                                         GenerateStats* stats) {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
  const auto t0 = std::chrono::steady_clock::now();
  // The model's voxel size is the footprint that limits the noise octaves; a vanishing one
  // keeps them all.
  const CloudModel model(params, o.octave_limit ? o.voxel_size : 1e-12, o.time);
  const double vs = o.voxel_size;
  const BlockLayout layout = block_layout(model, o);
  const openvdb::CoordBBox keep = layout.keep();
  // The upper bound of what the grid could hold must fit in memory.
  ensure_fits_in_memory(static_cast<uint64_t>(layout.voxels), sizeof(float), "the cloud's bounding box at this voxel size");
  // The model's (z-up) index of the grid's voxel (i, j, k).
  auto model_index = [&](int64_t i, int64_t j, int64_t k) {
    return o.y_up ? glm::dvec3(double(i), double(-k), double(j)) : glm::dvec3(double(i), double(j), double(k));
  };
  // Tests saved for these inputs are read instead of made; otherwise they are saved here.
  SavedTests saved(o.sparse ? o.reuse : nullptr, model, o, layout);

  // Owned until the tree takes them: a stop (cancel.hpp) or an error part-way frees what was made.
  tbb::enumerable_thread_specific<std::vector<std::unique_ptr<Leaf>>> leaves;
  tbb::enumerable_thread_specific<GenerateStats> counts;
  std::atomic<int64_t> done{0};
  const std::stop_token stop = current_stop_token();  // this call's, taken before the blocks fan out
  const int64_t report_every = std::max<int64_t>(1, layout.blocks / 100);
  tbb::parallel_for(int64_t(0), layout.blocks, [&](int64_t id) {
    throw_if_stopped(stop);
    if (o.progress && (done.fetch_add(1) + 1) % report_every == 0) o.progress(double(done.load()) / double(layout.blocks));
    const openvdb::Coord origin = layout.block_origin(id);
    GenerateStats& c = counts.local();
    uint8_t far[kLeaf * kLeaf * kLeaf];
    if (saved.reading()) {
      if (!saved.touched(id)) return;
      saved.count_read();
      const uint64_t* words = saved.far(id);
      if (std::all_of(words, words + kFarWords, [](uint64_t w) { return w == ~uint64_t(0); })) {
        c.voxels_visited += kLeaf * kLeaf * kLeaf;  // every voxel far: density 0
        return;
      }
      unpack_far(words, far);
    } else if (o.sparse) {
      // Voxel centres of this block span [origin, origin + 7] * vs (turned, y-up); skip it if no
      // shape is near.
      const glm::dvec3 a = model_index(origin.x(), origin.y(), origin.z()),
                       b = model_index(origin.x() + kLeaf - 1, origin.y() + kLeaf - 1, origin.z() + kLeaf - 1);
      const Aabb box{glm::min(a, b) * vs - o.origin_m, glm::max(a, b) * vs - o.origin_m};
      if (!model.may_touch(box.expanded(1e-9 * vs))) return;
      if (saved.saving()) saved.set_touched(id);
    }
    glm::dvec3 p[kLeaf * kLeaf * kLeaf];
    float d[kLeaf * kLeaf * kLeaf];
    int n = 0;
    for (int z = 0; z < kLeaf; ++z)
      for (int y = 0; y < kLeaf; ++y)
        for (int x = 0; x < kLeaf; ++x)
          p[n++] = model_index(origin.x() + x, origin.y() + y, origin.z() + z) * vs - o.origin_m;
    c.voxels_visited += n;
    if (o.sparse) {
      const bool keep_far = saved.reading() || saved.saving();
      c.noise_evaluations += model.densities(p, size_t(n), d, keep_far ? far : nullptr, saved.reading());
      if (saved.saving()) pack_far(far, saved.far(id));
    } else {
      for (int i = 0; i < n; ++i) d[i] = model.density(p[i]);
      c.noise_evaluations += n;
    }
    if (Leaf* leaf = leaf_of(origin, d, keep, c)) leaves.local().emplace_back(leaf);
  });
  saved.finish();

  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(vs));
  for (auto& list : leaves)
    for (std::unique_ptr<Leaf>& leaf : list) grid->tree().addLeaf(leaf.release());

  if (stats) {
    GenerateStats s;
    for (const GenerateStats& c : counts) {
      s.voxels_visited += c.voxels_visited;
      s.noise_evaluations += c.noise_evaluations;
      s.active_voxels += c.active_voxels;
    }
    s.voxels_in_bounds = layout.voxels;
    s.octaves_used = model.octaves_used();
    s.octaves_requested = params.octaves;
    s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    *stats = s;
  }
  return grid;
}

openvdb::FloatGrid::Ptr generate_temperature(const CloudParams& params, const openvdb::FloatGrid& density) {
  if (!(params.temperature_height > 0.0)) return nullptr;
  auto t = openvdb::FloatGrid::create(0.0f);
  t->setName("temperature");
  t->setGridClass(openvdb::GRID_FOG_VOLUME);
  t->setTransform(density.transform().copy());
  // Same topology as the density, then values from the altitude of each voxel.
  t->tree().topologyUnion(density.tree());
  for (auto it = t->beginValueOn(); it; ++it) {
    const openvdb::Vec3d w = t->indexToWorld(it.getCoord());
    const double h = (w.z() - params.temperature_base) / params.temperature_height;
    it.setValue(static_cast<float>(std::clamp(1.0 - h, 0.0, 1.0)));
  }
  return t;
}

}  // namespace nimbus::volume
