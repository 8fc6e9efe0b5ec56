// FastNoise2 loaded through its C API (see bench_noise_fastnoise2.hpp).
#include "bench_noise_fastnoise2.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace nimbus::cli::bench_noise {

// The C API's functions this bench calls (FastNoise_C.h at commit ba93f17).
struct FastNoise2::Api {
  int (*metadata_count)();
  const char* (*metadata_name)(int);
  void* (*new_from_metadata)(int, unsigned);
  void (*delete_node)(void*);
  unsigned (*active_feature_set)(const void*);
  int (*variable_count)(int);
  const char* (*variable_name)(int, int);
  bool (*set_variable_float)(void*, int, float);
  bool (*set_variable_int)(void*, int, int);
  int (*lookup_count)(int);
  const char* (*lookup_name)(int, int);
  bool (*set_lookup)(void*, int, const void*);
  void (*gen_grid3)(const void*, float*, float, float, float, int, int, int, float, float, float, int, float*);
};

namespace {

// FastSIMD::FeatureSet: a bit per feature flag (FastSIMD/Utility/FeatureEnums.h): x86 is bit
// 1, SSE..AVX2 bits 2..9, AVX-512 F/VL/DQ/BW bits 10..13.
unsigned feature_set(noise::SimdLevel level) {
  auto bits = [](int lo, int hi) {
    unsigned b = 0;
    for (int i = lo; i <= hi; ++i) b |= 1u << i;
    return b;
  };
  switch (level) {
    case noise::SimdLevel::Scalar: return 1u;
    case noise::SimdLevel::Sse41: return bits(1, 6);
    case noise::SimdLevel::Avx2: return bits(1, 9);
    case noise::SimdLevel::Avx512: return bits(1, 13);
  }
  return 1u;
}

// Names compared without case and spaces ("Feature Scale", "FeatureScale").
bool same_name(const char* a, const std::string& b) {
  if (!a) return false;
  std::string x;
  for (const char* p = a; *p; ++p)
    if (*p != ' ') x += char(std::tolower(static_cast<unsigned char>(*p)));
  std::string y;
  for (char c : b)
    if (c != ' ') y += char(std::tolower(static_cast<unsigned char>(c)));
  return x == y;
}

}  // namespace

FastNoise2::FastNoise2(const std::string& path) : path_(path), api_(std::make_unique<Api>()) {
  handle_ = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle_) {
    const char* e = dlerror();
    throw std::runtime_error("--fastnoise2 " + path + ": cannot load it (" + (e ? e : "unknown error") + ")");
  }
  auto sym = [&](auto& fn, const char* name) {
    void* p = dlsym(handle_, name);
    if (!p) throw std::runtime_error("--fastnoise2 " + path + ": no symbol " + name + " (not a FastNoise2 C API build?)");
    fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(p);
  };
  try {
    sym(api_->metadata_count, "fnGetMetadataCount");
    sym(api_->metadata_name, "fnGetMetadataName");
    sym(api_->new_from_metadata, "fnNewFromMetadata");
    sym(api_->delete_node, "fnDeleteNodeRef");
    sym(api_->active_feature_set, "fnGetActiveFeatureSet");
    sym(api_->variable_count, "fnGetMetadataVariableCount");
    sym(api_->variable_name, "fnGetMetadataVariableName");
    sym(api_->set_variable_float, "fnSetVariableFloat");
    sym(api_->set_variable_int, "fnSetVariableIntEnum");
    sym(api_->lookup_count, "fnGetMetadataNodeLookupCount");
    sym(api_->lookup_name, "fnGetMetadataNodeLookupName");
    sym(api_->set_lookup, "fnSetNodeLookup");
    sym(api_->gen_grid3, "fnGenUniformGrid3D");
  } catch (...) {
    dlclose(handle_);
    throw;
  }
}

FastNoise2::~FastNoise2() {
  if (handle_) dlclose(handle_);
}

bool FastNoise2::supports(noise::SimdLevel level) const {
  void* node = make(Fn2Graph::Perlin, level);
  const unsigned active = api_->active_feature_set(node);
  api_->delete_node(node);
  return active == feature_set(level);
}

// A node of the named type at the level, with the named variables set; throws naming what the
// library lacks.
void* FastNoise2::make(Fn2Graph graph, noise::SimdLevel level) const {
  auto node_of = [&](const std::string& type) {
    const int n = api_->metadata_count();
    for (int id = 0; id < n; ++id) {
      if (!same_name(api_->metadata_name(id), type)) continue;
      void* node = api_->new_from_metadata(id, feature_set(level));
      if (node) return std::pair<void*, int>{node, id};
    }
    throw std::runtime_error("--fastnoise2 " + path_ + ": no node type " + type);
  };
  auto set_float = [&](std::pair<void*, int> node, const std::string& var, float v) {
    const int n = api_->variable_count(node.second);
    for (int i = 0; i < n; ++i)
      if (same_name(api_->variable_name(node.second, i), var) && api_->set_variable_float(node.first, i, v)) return;
    throw std::runtime_error("--fastnoise2 " + path_ + ": no float variable " + var);
  };
  auto set_int = [&](std::pair<void*, int> node, const std::string& var, int v) {
    const int n = api_->variable_count(node.second);
    for (int i = 0; i < n; ++i)
      if (same_name(api_->variable_name(node.second, i), var) && api_->set_variable_int(node.first, i, v)) return;
    throw std::runtime_error("--fastnoise2 " + path_ + ": no integer variable " + var);
  };
  switch (graph) {
    case Fn2Graph::Perlin: {
      auto p = node_of("Perlin");
      set_float(p, "Feature Scale", 1.0f);
      return p.first;
    }
    case Fn2Graph::CellularDistance: {
      auto c = node_of("CellularDistance");
      set_float(c, "Feature Scale", 1.0f);
      return c.first;
    }
    case Fn2Graph::PerlinFbm6: {
      auto p = node_of("Perlin");
      set_float(p, "Feature Scale", 1.0f);
      auto f = node_of("FractalFBm");
      set_int(f, "Octaves", 6);
      set_float(f, "Lacunarity", 2.0f);
      const int n = api_->lookup_count(f.second);
      bool wired = false;
      for (int i = 0; i < n && !wired; ++i)
        if (same_name(api_->lookup_name(f.second, i), "Source")) wired = api_->set_lookup(f.first, i, p.first);
      api_->delete_node(p.first);  // the fractal holds its own reference
      if (!wired) {
        api_->delete_node(f.first);
        throw std::runtime_error("--fastnoise2 " + path_ + ": FractalFBm has no Source lookup");
      }
      return f.first;  // Gain keeps its default, 0.5
    }
  }
  throw std::logic_error("unknown FastNoise2 graph");
}

double FastNoise2::time_grid(Fn2Graph graph, noise::SimdLevel level, const noise::GridSpec& grid, int repeats,
                             std::vector<float>& out) const {
  void* node = make(graph, level);
  out.assign(size_t(grid.count()), 0.0f);
  const double secs = best_of(repeats, thread_cpu_seconds, [&] {
    api_->gen_grid3(node, out.data(), float(grid.origin[0]), float(grid.origin[1]), float(grid.origin[2]),
                    int(grid.res[0]), int(grid.res[1]), int(grid.res[2]), float(grid.spacing), float(grid.spacing),
                    float(grid.spacing), 0, nullptr);
  });
  api_->delete_node(node);
  return secs * 1e9 / double(grid.count());
}

const char* fn2_graph_name(Fn2Graph graph) {
  switch (graph) {
    case Fn2Graph::Perlin: return "Perlin";
    case Fn2Graph::PerlinFbm6: return "FractalFBm (6 octaves) of Perlin";
    case Fn2Graph::CellularDistance: return "CellularDistance";
  }
  return "?";
}

namespace {

double time_nimbus(const noise::NoiseParams& p, noise::SimdLevel level, const noise::GridSpec& grid, int repeats,
                   std::vector<float>& out) {
  const noise::NoiseField field(p);
  noise::BatchOptions opt;
  opt.simd = level;
  opt.parallel = false;
  out.assign(size_t(grid.count()), 0.0f);
  const double secs = best_of(repeats, thread_cpu_seconds, [&] { noise::evaluate_grid(field, grid, out, opt); });
  return secs * 1e9 / double(grid.count());
}

}  // namespace

void fastnoise2_rows(const FastNoise2& fn2, int64_t res, int repeats) {
  std::vector<noise::SimdLevel> levels;
  for (noise::SimdLevel l : {noise::SimdLevel::Avx2, noise::SimdLevel::Avx512})
    if (noise::simd_level_supported(l) && int(l) <= int(noise::best_simd_level()) && fn2.supports(l))
      levels.push_back(l);
  std::printf("### FastNoise2 beside nimbus (same run, same grids, one thread, thread CPU time)\n\n");
  std::printf("FastNoise2 from `%s`, called through its C API (`fnGenUniformGrid3D`, float coordinates), "
              "feature scale 1 (frequency 1), seed 0, capped at each level. Rows alternate nimbus and "
              "FastNoise2, best of %d.\n\n",
              fn2.path().c_str(), repeats);
  if (levels.empty()) {
    std::printf("(no AVX2 or AVX-512 level that both run on this CPU)\n\n");
    return;
  }
  struct Pair {
    const char* nimbus_name;
    noise::Kind kind;
    int octaves;
    Fn2Graph graph;
  };
  const Pair pairs[] = {{"gradient, 1 octave", noise::Kind::Gradient, 1, Fn2Graph::Perlin},
                        {"gradient, 6-octave fBm", noise::Kind::Gradient, 6, Fn2Graph::PerlinFbm6},
                        {"Worley, 1 octave", noise::Kind::Worley, 1, Fn2Graph::CellularDistance}};
  std::printf("| spacing | nimbus | FastNoise2 |");
  for (noise::SimdLevel l : levels) {
    const std::string n(noise::to_string(l));
    std::printf(" nimbus %s ns | FN2 %s ns | nimbus / FN2 (%s) |", n.c_str(), n.c_str(), n.c_str());
  }
  std::printf(" FN2 observed range |\n|---|---|---|");
  for (size_t i = 0; i < levels.size(); ++i) std::printf("---:|---:|---:|");
  std::printf("---|\n");
  std::vector<float> a, b;
  for (double spacing : {1.0 / 16.0, 1.37}) {
    noise::GridSpec g;
    g.origin = {0.137, 0.571, 0.913};
    g.spacing = spacing;
    g.res = {res, res, res};
    for (const Pair& p : pairs) {
      noise::NoiseParams np;
      np.kind = p.kind;
      np.fractal = p.octaves == 1 ? noise::Fractal::None : noise::Fractal::Fbm;
      np.octaves = p.octaves;
      std::printf("| %s | %s | %s |", spacing == 1.0 / 16.0 ? "1/16" : fmt("%g", spacing).c_str(), p.nimbus_name,
                  fn2_graph_name(p.graph));
      MinMax range;
      for (noise::SimdLevel l : levels) {
        const double tn = time_nimbus(np, l, g, repeats, a);
        const double tf = fn2.time_grid(p.graph, l, g, repeats, b);
        range = min_max(b);
        std::printf(" %s | %s | %.2f× |", ns_cell(tn).c_str(), ns_cell(tf).c_str(), tn / tf);
      }
      std::printf(" %s |\n", range_cell(range).c_str());
      std::fflush(stdout);
    }
  }
  std::printf("\n");
}

}  // namespace nimbus::cli::bench_noise
