// `nimbus bench look`: how far the slicer's multiple-scattering approximations are from the
// path-traced reference of the same model, and what each costs, front- and back-lit,
// isotropic, HG 0.7 and the default dual lobe; with the path tracer's own time and noise at
// several sample counts. Clouds alone over black, the sun at irradiance 3, no ambient.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/cli.hpp"
#include "cli/outputs.hpp"
#include "cli/render_args.hpp"
#include "cli/setting_flags.hpp"
#include "bench_lists.hpp"
#include "nimbus/base/validate.hpp"
#include "nimbus/render/core/cloud_framing.hpp"
#include "nimbus/render/core/cloud_source.hpp"
#include "nimbus/render/frame/frame_renderer.hpp"
#include "nimbus/render/gl/context.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "nimbus/render/image/image_metrics.hpp"
#include "nimbus/render/image/svg_plot.hpp"
#include "nimbus/render/reference/cloud_path_tracer.hpp"
#include "nimbus/render/reference/light_volume_builder.hpp"

namespace nimbus::cli {
namespace {

// The light volume's own default, unnamed in the rows' labels.
const int kDefaultRefine = static_cast<int>(render::LightVolumeSettings{}.photons_per_cell);

struct BenchLookArgs {
  std::string preset = "cumulus-mediocris";
  std::string res = "120x90";
  int ref_spp = 2048;
  std::string spp = "16,64,256";
  int slices = 128;
  std::string ms_grid = "48";       // light-volume rows: cells along the longest axis
  std::string ms_photons = std::to_string(render::LightVolumeSettings{}.photons);  // light-volume rows: photons from the sun
  std::string ms_lobes = "2";          // light-volume rows: scattering orders kept as lobes
  std::string ms_fits = "1";           // light-volume rows: 1 with eq. MS-4's fits, 0 without
  // light-volume rows: transport mean free paths deep beyond which light is diffused (0: all traced)
  std::string ms_diffusion = number_text(render::LightVolumeSettings{}.diffusion_depth);
  // light-volume rows: photons per cell face for finer cells, 0 the grid exactly
  std::string ms_refine = std::to_string(kDefaultRefine);
  // light-volume rows: transport mean free paths deep beyond which photons fly in the similar medium (0: never)
  std::string ms_similarity = number_text(render::LightVolumeSettings{}.similarity_depth);
  // light-volume rows: the share of the photons traced before the volume is taken, on the whole
  // build's grid (LightVolumeBuild; 1: the whole build)
  std::string ms_progressive = "1";
  std::string lighting = "front-lit,back-lit";          // which lightings to run
  std::string phases = "isotropic,hg,dual";             // which phases to run (prefixes of their names)
  std::string view = "side";  // side: the whole cloud framed level with it; below: looking up at its base
  std::string plot;
  std::string images;  // when set: every case's reference, its standard error and each method's image, as EXR
};

struct Octaves {
  std::string name;
  int octaves;
  double a, b;
  bool light_volume = false;
  int grid = 0;
  int photons = 0;
  int lobes = 2;
  bool fits = true;
  int refine = kDefaultRefine;  // LightVolumeSettings::photons_per_cell
  double diffusion = 0.0;       // LightVolumeSettings::diffusion_depth
  double similarity = 0.0;      // LightVolumeSettings::similarity_depth
  double share = 1.0;           // of the photons traced, progressively (LightVolumeBuild)
};

// An observer under the cloud looking up at its base, as a stratiform layer is seen: 1 km below
// the base (2 m above the ground at least), the base's centre 40 degrees up toward -z (the side
// view's direction). The layer fills the frame, where the side view of a thin sheet is a few rows.
render::Camera view_from_below(render::Camera cam, const std::vector<render::CloudVolume>& clouds) {
  glm::dvec3 lo, hi;
  render::cloud_bounds(clouds, lo, hi);
  const glm::dvec3 target(0.5 * (lo.x + hi.x), lo.y, 0.5 * (lo.z + hi.z));
  const double eye_y = std::max(2.0, lo.y - 1000.0);
  const double rise = 40.0 * M_PI / 180.0;
  cam.eye = glm::dvec3(target.x, eye_y, target.z + (target.y - eye_y) / std::tan(rise));
  cam.look_at = target;
  return render::fit_far_plane(cam, clouds);
}

// The reference's per-pixel standard error as an image (RGB; alpha 1), for --images.
render::Image std_error_image(const render::PathTracedImage& ref) {
  render::Image img(ref.image.width, ref.image.height);
  for (std::size_t p = 0; p < static_cast<std::size_t>(img.width) * img.height; ++p) {
    for (int c = 0; c < 3; ++c) img.rgba[4 * p + c] = ref.std_error[3 * p + c];
    img.rgba[4 * p + 3] = 1.0f;
  }
  img.metadata = ref.image.metadata;
  img.metadata["contents"] = "per-pixel standard error of the reference's mean, RGB";
  return img;
}

struct Lighting {
  const char* name;
  glm::dvec3 to_sun;
};
struct PhaseCase {
  const char* name;
  render::Phase phase;
};
const Lighting kLightings[] = {{"front-lit", {0.8, 0.55, -0.25}}, {"back-lit", {-0.5, 0.55, -0.7}}};
const PhaseCase kPhases[] = {{"isotropic", render::Phase{}},
                             {"hg:0.7", render::Phase{render::PhaseKind::HenyeyGreenstein, 0.7}},
                             {"dual:0.7,-0.25,0.8", render::dual_lobe_phase(0.7, -0.25, 0.8)}};

// The slicer's rows: single scattering, the octaves, and a light volume for every combination of
// the --ms-* lists.
std::vector<Octaves> method_rows(const BenchLookArgs& a) {
  std::vector<Octaves> methods = {{"single scattering", 0, 0.5, 0.5},
                                  {"2 octaves (a 0.5, b 0.5)", 2, 0.5, 0.5},
                                  {"3 octaves (a 0.5, b 0.5)", 3, 0.5, 0.5},
                                  {"3 octaves (a 0.5, b 0.6)", 3, 0.5, 0.6}};
  for (int grid : parse_ints("--ms-grid", a.ms_grid)) {
    check_flag(render::Setting::MsGrid, grid);
    for (int photons : parse_ints("--ms-photons", a.ms_photons, int(render::setting(render::Setting::MsPhotons).max)))
      for (int lobes : parse_ints("--ms-lobes", a.ms_lobes, 2, 0))
        for (int fits : parse_ints("--ms-fits", a.ms_fits, 1, 0))
          for (int refine : parse_ints("--ms-refine", a.ms_refine, 1000000000, 0))
            for (double diffusion : parse_doubles("--ms-diffusion-depth", a.ms_diffusion, 0.0, 1000.0))
              for (double similarity : parse_doubles("--ms-similarity-depth", a.ms_similarity, 0.0, 1000.0))
                for (double share : parse_doubles("--ms-progressive", a.ms_progressive, 1.0 / 1024.0, 1.0)) {
              methods.push_back({"light volume " + std::to_string(grid) + " cells, " + std::to_string(photons) + " photons, " +
                                     (lobes == 0 ? std::string("no lobes") : std::to_string(lobes) + " lobe orders") +
                                     (fits ? "" : ", no fits") +
                                     (refine == kDefaultRefine ? ""
                                      : refine == 0  ? ", exact grid"
                                                     : ", finer to " + std::to_string(refine) + " photons a cell") +
                                     (diffusion == 0.0 ? ""
                                                       : ", diffused deeper than " + number_text(diffusion) + " mfp") +
                                     (similarity == 0.0 ? ""
                                                        : ", similar deeper than " + number_text(similarity) + " mfp") +
                                     (share == 1.0 ? "" : ", its first " + number_text(share) + " traced"),
                                 0, 0.5, 0.5, true, grid, photons, lobes, fits != 0, refine, diffusion, similarity, share});
            }
  }
  return methods;
}

// The flags, checked before any work: the image size, the tracer's sample counts and the preset.
struct LookPlan {
  int w = 0, h = 0;
  std::vector<int> spps;
  render::PresetCloud preset;
  std::vector<Octaves> methods;
};

LookPlan check_args(const BenchLookArgs& a) {
  if (a.view != "side" && a.view != "below") throw UsageError("--view: expected side or below, got '" + a.view + "'");
  check_case_list("--lighting", a.lighting, {"front-lit", "back-lit"});
  check_case_list("--phases", a.phases, {"isotropic", "hg:0.7", "dual:0.7,-0.25,0.8"});
  LookPlan p;
  std::tie(p.w, p.h) = parse_resolution("--res", a.res);
  p.spps = parse_ints("--spp", a.spp);
  if (a.ref_spp < 1 || a.ref_spp > (1 << 20)) throw UsageError("--ref-spp: must be in [1, 1048576]");
  if (a.slices < 2 || a.slices > 4096) throw UsageError("--slices: must be in [2, 4096]");
  check_outputs({{"--plot", a.plot}});
  try {
    p.preset = render::load_preset_cloud(a.preset);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--preset: ") + e.what());
  }
  if (!a.images.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(a.images, ec);
    if (ec || !std::filesystem::is_directory(a.images))
      throw std::runtime_error("--images: cannot make the directory '" + a.images + "'" + (ec ? ": " + ec.message() : ""));
  }
  return p;
}

void print_header(const BenchLookArgs& a, const LookPlan& p, const std::string& gl_renderer) {
  std::printf("# nimbus bench look: %s, %dx%d, seen from %s, clouds alone over black, sun irradiance 3, no ambient, %s\n", a.preset.c_str(),
              p.w, p.h, a.view == "below" ? "below" : "the side", gl_renderer.c_str());
  std::printf("# reference: the path tracer at %d samples per pixel (its own noise in its row); error: relative RMSE over\n"
              "#   covered pixels against it (compare_images), which includes the reference's noise; less ref. noise: the same\n"
              "#   with the reference's own variance taken out (noise_corrected_rel_rmse), the error against a converged\n"
              "#   reference; slicer: %d slices,\n"
              "#   light 256^2, GPU ms of its passes\n\n",
              a.ref_spp, a.slices);
  std::printf("| lighting | phase | method | ms | rel. RMSE | less ref. noise | bias | noise (mean rel. std. error) | light volume build, CPU ms | cells used |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|---:|---|\n");
}

// One case (a lighting and a phase): the cloud, the camera, the sun and the path-traced reference.
struct LookCase {
  const Lighting& lighting;
  const PhaseCase& phase;
  std::vector<render::CloudVolume> clouds;
  render::Camera camera;
  render::Light light;
  render::PathTracedImage reference;
  std::filesystem::path stem;  // --images: the case's file names start here
};

LookCase look_case(const BenchLookArgs& a, const LookPlan& p, const Lighting& l, const PhaseCase& ph) {
  LookCase c{l, ph, {}, {}, {}, {}, std::filesystem::path(a.images) / (slug(l.name) + "_" + slug(ph.name))};
  render::CloudOptics optics;
  optics.phase = ph.phase;
  c.clouds = {render::generate_preset_cloud(p.preset, std::nullopt, 0.0, optics)};
  render::Camera cam;
  cam.width = p.w;
  cam.height = p.h;
  cam.fov_deg = 44.8;
  c.camera = a.view == "below" ? view_from_below(cam, c.clouds) : render::frame_clouds(cam, c.clouds, false);
  c.light.direction_to_sun = l.to_sun;
  render::PathTracerSettings ps;
  ps.samples_per_pixel = a.ref_spp;
  c.reference = render::render_cloud_path_traced(c.clouds, c.camera, c.light, ps);
  std::printf("| %s | %s | path tracer, %d spp (reference) | %.0f | 0 | 0 | 0 | %.4f | | |\n", l.name, ph.name, a.ref_spp,
              1000.0 * c.reference.seconds, c.reference.mean_relative_error);
  if (!a.images.empty()) {
    render::write_exr(c.stem.string() + "_reference.exr", c.reference.image);
    render::write_exr(c.stem.string() + "_reference-std-error.exr", std_error_image(c.reference));
  }
  return c;
}

// The path tracer's own rows: its error against the reference as samples grow (other streams).
render::PlotSeries path_tracer_rows(const LookPlan& p, const LookCase& c) {
  render::PlotSeries traced;  // one line per case: error against time as samples grow
  traced.name = std::string("path tracer, ") + c.lighting.name + ", " + c.phase.name;
  render::PathTracerSettings ps;
  for (int spp : p.spps) {
    ps.samples_per_pixel = spp;
    ps.seed = 7;  // other streams than the reference's
    const render::PathTracedImage pt = render::render_cloud_path_traced(c.clouds, c.camera, c.light, ps);
    const render::ImageError e = render::compare_images(pt.image, c.reference.image);
    const double clean = render::noise_corrected_rel_rmse(pt.image, c.reference.image, c.reference.std_error);
    std::printf("| %s | %s | path tracer, %d spp | %.0f | %.4f | %.4f | %+.4f | %.4f | | |\n", c.lighting.name,
                c.phase.name, spp, 1000.0 * pt.seconds, e.rel_rmse, clean, e.mean_bias, pt.mean_relative_error);
    traced.x.push_back(1000.0 * pt.seconds);
    traced.y.push_back(e.rel_rmse);
  }
  return traced;
}

render::FrameSettings slicer_settings(const BenchLookArgs& a, const Octaves& m) {
  render::FrameSettings fs;
  fs.slices.slices = a.slices;
  fs.slices.ambient = false;
  fs.slices.multiple.octaves = m.octaves;
  fs.slices.multiple.occlusion = m.a;
  fs.slices.multiple.contribution = m.b;
  if (m.light_volume) {
    fs.slices.multiple.method = render::MultipleScatteringMethod::LightVolume;
    fs.slices.multiple.light_volume.resolution = m.grid;
    fs.slices.multiple.light_volume.photons = m.photons;
    fs.slices.multiple.light_volume.lobe_orders = m.lobes;
    fs.slices.multiple.light_volume.fits = m.fits;
    fs.slices.multiple.light_volume.photons_per_cell = m.refine;
    fs.slices.multiple.light_volume.diffusion_depth = m.diffusion;
    fs.slices.multiple.light_volume.similarity_depth = m.similarity;
  }
  return fs;
}

// One slicer row: the best GPU time of five frames after the first (which builds the light
// volume), its error against the reference, and the light volume's build time and grid. A row
// with a share of the photons takes the volume of a progressive build after that share.
void slicer_row(const BenchLookArgs& a, const LookCase& c, const Octaves& m, render::PlotSeries& series) {
  const render::FrameSettings fs = slicer_settings(a, m);
  render::FrameRenderer fr(std::nullopt, c.light, fs);
  fr.set_clouds(c.clouds);
  render::FrameStats first;
  if (m.share < 1.0) {
    render::LightVolumeBuild build(c.clouds, c.light, fs.slices.multiple.light_volume);
    build.trace(std::max<std::int64_t>(1, std::llround(m.share * static_cast<double>(build.photons()))));
    const render::LightVolume v = build.volume();
    fr.set_light_volume(v);
    first.light_volume_build_ms = 1000.0 * v.build_seconds;
    fr.render(c.camera);
  } else {
    fr.render(c.camera, &first);  // programs compiled, buffers made, the light volume built
  }
  double best = 1e300;
  render::Image img;
  for (int rep = 0; rep < 5; ++rep) {
    render::FrameStats st;
    img = fr.render(c.camera, &st);
    best = std::min(best, st.clouds.total_ms);
  }
  if (!a.images.empty()) {
    img.metadata["bench_method"] = m.name;
    render::write_exr(c.stem.string() + "_" + slug(m.name) + ".exr", img);
  }
  const render::ImageError e = render::compare_images(img, c.reference.image);
  char build[32] = "", used[64] = "";
  if (m.light_volume) {
    std::snprintf(build, sizeof build, "%.0f", first.light_volume_build_ms);
    const render::LightVolume g = render::light_volume_grid(c.clouds, fs.slices.multiple.light_volume);
    std::snprintf(used, sizeof used, "%dx%dx%d, %.0f m", g.size[0], g.size[1], g.size[2],
                  std::max({g.cell_m.x, g.cell_m.y, g.cell_m.z}));
  }
  const double clean = render::noise_corrected_rel_rmse(img, c.reference.image, c.reference.std_error);
  std::printf("| %s | %s | slicer, %s | %.1f | %.4f | %.4f | %+.4f | | %s | %s |\n", c.lighting.name, c.phase.name,
              m.name.c_str(), best, e.rel_rmse, clean, e.mean_bias, build, used);
  series.x.push_back(best);
  series.y.push_back(e.rel_rmse);
}

int run_bench_look(const BenchLookArgs& a) {
  const LookPlan p = check_args(a);
  const std::vector<Octaves> methods = method_rows(a);
  const auto gl = render::GlContext::create_headless();
  print_header(a, p, gl->renderer());
  std::vector<render::PlotSeries> series(methods.size());
  for (std::size_t m = 0; m < methods.size(); ++m) series[m].name = std::string("slicer, ") + methods[m].name;
  for (const Lighting& l : kLightings)
    for (const PhaseCase& ph : kPhases) {
      if (!chosen(a.lighting, l.name) || !chosen(a.phases, ph.name)) continue;
      const LookCase c = look_case(a, p, l, ph);
      series.push_back(path_tracer_rows(p, c));
      for (std::size_t m = 0; m < methods.size(); ++m) slicer_row(a, c, methods[m], series[m]);
      std::fflush(stdout);
    }
  if (!a.plot.empty()) {
    render::Plot plot;
    plot.title = "Clouds against the path tracer, " + a.preset + ", " + a.res;
    plot.x_title = "time per frame (ms): slicer GPU passes, path tracer CPU (2 cores)";
    plot.y_title = "relative RMSE vs path-traced reference";
    plot.series = series;
    render::write_svg_plot(a.plot, plot);
  }
  return 0;
}

}  // namespace

void add_bench_look(CLI::App& bench, Action& action) {
  auto a = std::make_shared<BenchLookArgs>();
  CLI::App* cmd = bench.add_subcommand(
      "look", "Multiple scattering: the slicer's approximations against the path-traced reference, and the tracer's noise");
  cmd->add_option("--preset", a->preset, "The cloud")->capture_default_str();
  cmd->add_option("--res", a->res, "Image size WxH")->capture_default_str();
  cmd->add_option("--ref-spp", a->ref_spp, "Samples per pixel of the reference")->capture_default_str();
  cmd->add_option("--spp", a->spp, "Comma-separated sample counts for the tracer's own rows")->capture_default_str();
  cmd->add_option("--slices", a->slices, "Slicer slices")->capture_default_str();
  cmd->add_option("--ms-grid", a->ms_grid, "Comma-separated light-volume resolutions (cells along the longest axis)")
      ->capture_default_str();
  cmd->add_option("--ms-photons", a->ms_photons, "Comma-separated light-volume photon counts")->capture_default_str();
  cmd->add_option("--ms-lobes", a->ms_lobes, "Comma-separated light-volume lobe orders, 0 to 2 (0: harmonics alone)")
      ->capture_default_str();
  cmd->add_option("--ms-fits", a->ms_fits, "Comma-separated: 1 light volume with its linear fits in each cell, 0 without")
      ->capture_default_str();
  cmd->add_option("--ms-diffusion-depth", a->ms_diffusion,
                  "Comma-separated transport mean free paths inside the clouds beyond which the light volume's photons "
                  "hand their light to diffusion (0: all traced)")
      ->capture_default_str();
  cmd->add_option("--ms-refine", a->ms_refine,
                  "Comma-separated photons per cell face down to which the light volume takes finer cells than --ms-grid "
                  "(0: --ms-grid exactly)")
      ->capture_default_str();
  cmd->add_option("--ms-similarity-depth", a->ms_similarity,
                  "Comma-separated transport mean free paths inside the clouds beyond which the light volume's photons, "
                  "past their lobe orders, fly in the similar isotropic medium (0: the true phase everywhere)")
      ->capture_default_str();
  cmd->add_option("--ms-progressive", a->ms_progressive,
                  "Comma-separated shares of the photons in [1/1024, 1] traced before the light volume is taken, on the whole "
                  "build's grid: a progressive build's early volume (1: the whole build)")
      ->capture_default_str();
  cmd->add_option("--lighting", a->lighting, "Comma-separated lightings to run: front-lit, back-lit")->capture_default_str();
  cmd->add_option("--phases", a->phases, "Comma-separated phases to run: isotropic, hg, dual (names or their prefixes)")
      ->capture_default_str();
  cmd->add_option("--view", a->view, "side: the whole cloud framed level with it; below: looking up at its base from 1 km under it")
      ->capture_default_str();
  cmd->add_option("--plot", a->plot, "Write an SVG plot of time against error here");
  cmd->add_option("--images", a->images,
                  "Write each case's reference, its standard error and every method's image here as EXR "
                  "(<lighting>_<phase>_<method>.exr), to see where the error lies");
  cmd->callback([&action, a] { action = [a] { return run_bench_look(*a); }; });
}

}  // namespace nimbus::cli
