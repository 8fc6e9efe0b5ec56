// Scripted viewer runs (view_script.hpp).
#include "view_script.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "nimbus/base/input_limits.hpp"
#include "nimbus/render/core/world_axes.hpp"
#include "nimbus/render/sky/view_state.hpp"
#include "nimbus/volume/json_io.hpp"
#include "nimbus/volume/sky_ranges.hpp"

namespace nimbus::viewer {
namespace {

using json = nlohmann::json;

[[noreturn]] void bad(const std::string& m) { throw std::invalid_argument(m); }

double number(const json& v, const std::string& key, double lo, double hi) { return volume::json_number(v, key, lo, hi); }
int integer(const json& v, const std::string& key, int lo, int hi) { return volume::json_integer(v, key, lo, hi); }
glm::dvec3 vec3(const json& v, const std::string& key) { return volume::json_vec3(v, key, 1e7); }

const std::map<std::string, Key>& key_names() {
  static const std::map<std::string, Key> k = {
      {"space", Key::Space}, {"left", Key::Left}, {"right", Key::Right}, {"g", Key::G},         {"h", Key::H},
      {"tab", Key::Tab},     {"f5", Key::F5},     {"f12", Key::F12},     {"ctrl+s", Key::CtrlS}, {"ctrl+o", Key::CtrlO},
      {"escape", Key::Escape}};
  return k;
}

}  // namespace

Script load_script(const std::string& path) {
  const json doc = volume::read_json_file(path, "script");
  const std::string where = "script '" + path + "'";
  if (!doc.is_object()) bad(where + " must be a JSON object");
  Script s;
  // No "version": a script from before it, whose camera keys were Y-up (view_state.hpp).
  const int version = doc.contains("version") ? integer(doc["version"], where + ".version", 1, render::kViewStateVersion) : 1;
  for (const auto& [k, v] : doc.items()) {
    const std::string key = where + "." + echo(k);
    if (k == "version") {
      continue;
    } else if (k == "size") {
      if (!v.is_array() || v.size() != 2) bad(key + " must be [width, height]");
      s.width = integer(v[0], key + "[0]", 16, 8192);
      s.height = integer(v[1], key + "[1]", 16, 8192);
    } else if (k == "frames") {
      s.frames = integer(v, key, 1, 100000);
    } else if (k == "dt") {
      s.dt_s = number(v, key, 0.0, 60.0);
    } else if (k == "screenshot_every") {
      s.screenshot_every = integer(v, key, 0, 100000);
    } else if (k == "adaptive") {
      s.adaptive = volume::json_bool(v, key);
    } else if (k == "samples") {
      s.samples = integer(v, key, 0, 4096);
    } else if (k == "temporal") {
      s.temporal = volume::json_bool(v, key);
    } else if (k == "record") {
      if (!v.is_string() || v.get<std::string>().empty()) bad(key + " must be a file name");
      s.record = v.get<std::string>();
    } else if (k == "camera") {
      if (!v.is_array()) bad(key + " must be an array of {frame, eye, look_at}");
      for (std::size_t i = 0; i < v.size(); ++i) {
        const std::string ck = key + "[" + std::to_string(i) + "]";
        if (!v[i].is_object() || !v[i].contains("frame") || !v[i].contains("eye") || !v[i].contains("look_at") || v[i].size() != 3)
          bad(ck + " must be {\"frame\": N, \"eye\": [x, y, z], \"look_at\": [x, y, z]}");
        ScriptCameraKey c;
        c.frame = integer(v[i]["frame"], ck + ".frame", 0, 100000);
        c.eye = vec3(v[i]["eye"], ck + ".eye");
        c.look_at = vec3(v[i]["look_at"], ck + ".look_at");
        if (version >= 2) {
          c.eye = render::world_to_render(c.eye);
          c.look_at = render::world_to_render(c.look_at);
        }
        if (!s.camera.empty() && c.frame <= s.camera.back().frame) bad(ck + ".frame must increase");
        s.camera.push_back(c);
      }
    } else if (k == "events") {
      if (!v.is_array()) bad(key + " must be an array of events");
      for (std::size_t i = 0; i < v.size(); ++i) {
        const std::string ek = key + "[" + std::to_string(i) + "]";
        const json& e = v[i];
        if (!e.is_object() || !e.contains("frame")) bad(ek + " must be an object with a frame");
        ScriptEvent ev;
        ev.frame = integer(e["frame"], ek + ".frame", 0, 100000);
        int kinds = 0;
        for (const auto& [ik, iv] : e.items()) {
          const std::string ikey = ek + "." + echo(ik);
          if (ik == "frame") continue;
          ++kinds;
          if (ik == "key") {
            if (!iv.is_string() || !key_names().count(iv.get<std::string>())) {
              std::string known;
              for (const auto& [n, _] : key_names()) known += (known.empty() ? "" : ", ") + n;
              bad(ikey + " must be one of " + known);
            }
            ev.kind = ScriptEvent::Kind::Key;
            ev.key = key_names().at(iv.get<std::string>());
          } else if (ik == "drag") {
            if (!iv.is_array() || iv.size() != 2) bad(ikey + " must be [dx, dy] pixels");
            ev.kind = ScriptEvent::Kind::Drag;
            ev.amount = {number(iv[0], ikey + "[0]", -1e5, 1e5), number(iv[1], ikey + "[1]", -1e5, 1e5)};
          } else if (ik == "button") {
            if (!iv.is_string() || (iv != "left" && iv != "right")) bad(ikey + " must be left or right");
            ev.button = iv == "left" ? 0 : 1;
            --kinds;
          } else if (ik == "scroll") {
            ev.kind = ScriptEvent::Kind::Scroll;
            ev.amount = {number(iv, ikey, -100, 100), 0.0};
          } else if (ik == "sun") {
            if (!iv.is_array() || iv.size() != 2) bad(ikey + " must be [elevation, azimuth] degrees");
            ev.kind = ScriptEvent::Kind::Sun;
            ev.amount = {number(iv[0], ikey + "[0]", volume::kSunElevationRangeDeg.lo, volume::kSunElevationRangeDeg.hi),
                         number(iv[1], ikey + "[1]", volume::kSunAzimuthRangeDeg.lo, volume::kSunAzimuthRangeDeg.hi)};
            if (ev.amount.y == volume::kSunAzimuthRangeDeg.hi) ev.amount.y = volume::kSunAzimuthRangeDeg.lo;  // north, as sky files read it
          } else if (ik == "save_sky") {
            if (!iv.is_string() || iv.get<std::string>().empty()) bad(ikey + " must be a file name");
            ev.kind = ScriptEvent::Kind::SaveSky;
            ev.path = iv.get<std::string>();
          } else {
            bad(ikey + ": unknown key (known: frame, key, drag, button, scroll, sun, save_sky)");
          }
        }
        if (kinds != 1) bad(ek + " must hold exactly one of key, drag, scroll, sun, save_sky");
        s.events.push_back(ev);
      }
    } else {
      bad(key + ": unknown key (known: version, size, frames, dt, screenshot_every, adaptive, samples, temporal, record, camera, events)");
    }
  }
  // An event after the last frame would never happen: say so rather than skip it.
  for (std::size_t i = 0; i < s.events.size(); ++i)
    if (s.events[i].frame >= s.frames)
      bad(where + ".events[" + std::to_string(i) + "].frame " + std::to_string(s.events[i].frame) +
          " is past the last frame (" + std::to_string(s.frames - 1) + "; frames: " + std::to_string(s.frames) + ")");
  return s;
}

int run_script(const Script& s, Viewer& viewer, const std::function<void()>& present) {
  viewer.adaptive().enabled = s.adaptive;
  json record = json::array();
  int failures = 0;
  for (int f = 0; f < s.frames && !viewer.quit_requested(); ++f) {
    if (f > 0) viewer.advance(s.dt_s);
    // Camera keyframes: linear between the two around this frame, held beyond them.
    if (!s.camera.empty()) {
      const ScriptCameraKey* a = nullptr;
      const ScriptCameraKey* b = nullptr;
      for (const ScriptCameraKey& c : s.camera) {
        if (c.frame <= f) a = &c;
        if (c.frame >= f && !b) b = &c;
      }
      if (!a) a = b;
      if (!b) b = a;
      const double w = b->frame > a->frame ? static_cast<double>(f - a->frame) / (b->frame - a->frame) : 0.0;
      viewer.set_camera(glm::mix(a->eye, b->eye, w), glm::mix(a->look_at, b->look_at, w));
    }
    for (const ScriptEvent& e : s.events) {
      if (e.frame != f) continue;
      switch (e.kind) {
        case ScriptEvent::Kind::Key: viewer.key(e.key); break;
        case ScriptEvent::Kind::Drag: viewer.drag(e.button, e.amount.x, e.amount.y); break;
        case ScriptEvent::Kind::Scroll: viewer.scroll(e.amount.x); break;
        case ScriptEvent::Kind::Sun: viewer.set_sun(e.amount.x, e.amount.y); break;
        case ScriptEvent::Kind::SaveSky: viewer.save_sky(e.path); break;
      }
      if (!viewer.message().empty()) std::fprintf(stderr, "frame %d: %s\n", f, echo(viewer.message(), 1000).c_str());
      if (!viewer.shader_error().empty())
        std::fprintf(stderr, "frame %d: shader error: %s\n", f, echo(viewer.shader_error(), 2000).c_str());
    }
    if (viewer.quit_requested()) break;
    // The adaptive quality's clock is the script's (f * dt): when it refines does not depend on
    // how fast the machine is; what it picks still depends on the measured frame times.
    viewer.draw(s.width, s.height, f * s.dt_s);
    present();
    std::string shot;
    if (s.screenshot_every > 0 && f % s.screenshot_every == 0) {
      try {
        shot = viewer.report().quality_level == 0 ? viewer.save_frame() : viewer.screenshot(s.width, s.height);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "nimbus view: screenshot at frame %d: %s\n", f, echo(e.what(), 1000).c_str());
        ++failures;
      }
    }
    const FrameReport& r = viewer.report();
    record.push_back({{"frame", f},
                      {"sky_time", viewer.state().sky_time_s},
                      {"evolution_time", r.info.evolution_time_s},
                      {"keyframe", r.info.keyframe},
                      {"blend", r.info.blend},
                      {"uploaded", r.info.uploaded},
                      {"waited", r.info.waited},
                      {"paused", viewer.state().paused},
                      {"cpu_ms", r.cpu_ms},
                      {"gpu_ms", r.stats.scene.total_ms + r.stats.clouds.total_ms},
                      {"quality_level", r.quality_level},
                      {"samples", r.samples},
                      {"temporal_frames", r.temporal_frames},
                      {"width", r.info.width},
                      {"height", r.info.height},
                      {"slices", r.info.slices},
                      {"multiple", r.info.multiple},
                      {"light_volume_ms", r.info.light_volume_ms},
                      {"screenshot", shot}});
  }
  if (!s.record.empty()) {
    try {
      volume::write_json_file(s.record, record, "record");
    } catch (const std::exception& e) {
      std::fprintf(stderr, "nimbus view: record '%s': %s\n", echo(s.record, 200).c_str(), echo(e.what(), 1000).c_str());
      ++failures;
    }
  }
  failures += viewer.failures();  // saves, loads and screenshots of key and save_sky events
  return failures == 0 ? 0 : 1;
}

}  // namespace nimbus::viewer
