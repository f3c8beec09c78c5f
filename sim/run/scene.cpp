#include "sim/run/scene.hpp"

#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include <nlohmann/json.hpp>

#include "model/base/error.hpp"
#include "model/base/input_file.hpp"
#include "model/mesh_io.hpp"
#include "sim/base/json_input.hpp"
#include "sim/run/simulate.hpp"

namespace tessim::sim {

namespace {

constexpr std::uint64_t kSceneFileLimit = std::uint64_t{16} << 20;
constexpr double kPi = 3.14159265358979323846;

using nlohmann::json;

struct Reader {
  std::string file;

  [[noreturn]] void fail(const std::string& element, const std::string& reason) const {
    throw InputError(file, element, reason);
  }
  void only_keys(const json& j, const std::string& element, const std::set<std::string>& allowed) const {
    if (!j.is_object()) fail(element, "is not an object");
    for (const auto& [key, value] : j.items())
      if (!allowed.count(key)) fail(element.empty() ? key : element + "." + key, "unknown key");
  }
  double number(const json& j, const std::string& element, double lo, double hi) const {
    if (!j.is_number()) fail(element, "is not a number");
    const double v = j.get<double>();
    if (!std::isfinite(v) || v < lo || v > hi)
      fail(element, j.dump() + " is outside " + json(lo).dump() + ".." + json(hi).dump());
    return v;
  }
  glm::dvec3 vec3(const json& j, const std::string& element) const {
    if (!j.is_array() || j.size() != 3) fail(element, "is not [x, y, z]");
    glm::dvec3 v;
    for (int i = 0; i < 3; ++i) v[i] = number(j[static_cast<std::size_t>(i)], element + "[" + std::to_string(i) + "]", -1e12, 1e12);
    return v;
  }
  std::string text(const json& j, const std::string& element) const {
    if (!j.is_string() || j.get<std::string>().empty()) fail(element, "is not a non-empty string");
    return j.get<std::string>();
  }
};

Mesh placed(const Mesh& mesh, const SceneInstance& instance) {
  Mesh out = mesh;
  const double a = instance.rotate_y_deg * kPi / 180.0, c = std::cos(a), s = std::sin(a);
  auto rotate = [c, s](const glm::dvec3& v) { return glm::dvec3(c * v.x + s * v.z, v.y, -s * v.x + c * v.z); };
  for (glm::dvec3& p : out.positions) p = instance.translate + rotate(instance.scale * p);
  // Normals by the inverse transpose: a flattened box keeps normals that face out of its faces.
  for (glm::dvec3& n : out.normals) n = glm::normalize(rotate(n / instance.scale));
  return out;
}

}  // namespace

Scene load_scene(const std::string& path) {
  const Reader r{path};
  const json j = parse_json_text(read_whole_file(path, kSceneFileLimit, "file"), path);
  r.only_keys(j, "", {"format", "version", "description", "clock_mhz", "viewport", "draws", "camera_path"});
  if (j.value("format", std::string()) != "tessim-scene") r.fail("format", "must be \"tessim-scene\"");
  if (!j.contains("version") || j["version"] != 1) r.fail("version", "must be 1");
  Scene scene;
  scene.source = path;
  if (j.contains("clock_mhz")) scene.clock_mhz = r.number(j["clock_mhz"], "clock_mhz", 1e-3, 1e6);
  if (j.contains("viewport")) {
    const json& v = j["viewport"];
    if (!v.is_array() || v.size() != 2) r.fail("viewport", "is not [width, height]");
    scene.viewport_width = static_cast<int>(r.number(v[0], "viewport[0]", 1, 16384));
    scene.viewport_height = static_cast<int>(r.number(v[1], "viewport[1]", 1, 16384));
    if (v[0].get<double>() != scene.viewport_width || v[1].get<double>() != scene.viewport_height)
      r.fail("viewport", "must be whole pixels");
  }
  if (!j.contains("draws") || !j["draws"].is_array() || j["draws"].empty()) r.fail("draws", "is not a non-empty list");
  if (!j.contains("camera_path") || !j["camera_path"].is_array() || j["camera_path"].empty())
    r.fail("camera_path", "is not a non-empty list of cameras (one frame each)");
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  for (std::size_t d = 0; d < j["draws"].size(); ++d) {
    const json& dj = j["draws"][d];
    const std::string at = "draws[" + std::to_string(d) + "]";
    r.only_keys(dj, at, {"name", "mesh", "instances", "tessellation", "L", "rule", "pixels_per_segment",
                         "outline_tolerance"});
    SceneDraw draw;
    draw.name = dj.contains("name") ? r.text(dj["name"], at + ".name") : "draw " + std::to_string(d);
    if (!dj.contains("mesh")) r.fail(at + ".mesh", "is missing");
    std::filesystem::path mesh = r.text(dj["mesh"], at + ".mesh");
    draw.mesh = (mesh.is_relative() ? folder / mesh : mesh).string();
    const std::string kind = dj.contains("tessellation") ? r.text(dj["tessellation"], at + ".tessellation") : "uniform";
    if (kind == "none") draw.tessellation = DrawTessellation::None;
    else if (kind == "uniform") draw.tessellation = DrawTessellation::Uniform;
    else if (kind == "adaptive") draw.tessellation = DrawTessellation::Adaptive;
    else r.fail(at + ".tessellation", "'" + kind + "' is not none, uniform or adaptive");
    auto only_for = [&](const char* key, bool allowed, const char* what) {
      if (dj.contains(key) && !allowed) r.fail(at + "." + key, std::string("only ") + what + " draws take it");
    };
    only_for("L", draw.tessellation == DrawTessellation::Uniform, "uniform");
    only_for("rule", draw.tessellation == DrawTessellation::Adaptive, "adaptive");
    if (dj.contains("L")) {
      const double L = r.number(dj["L"], at + ".L", 1, 64);
      if (L != std::floor(L)) r.fail(at + ".L", "must be a whole number 1..64");
      draw.L = static_cast<int>(L);
    }
    if (draw.tessellation == DrawTessellation::Adaptive) {
      const std::string rule = dj.contains("rule") ? r.text(dj["rule"], at + ".rule") : "screen";
      if (rule == "screen") draw.rule = AdaptiveRule::Screen;
      else if (rule == "silhouette") draw.rule = AdaptiveRule::Silhouette;
      else if (rule == "contour") draw.rule = AdaptiveRule::Contour;
      else r.fail(at + ".rule", "'" + rule + "' is not screen, silhouette or contour");
    }
    only_for("pixels_per_segment", draw.tessellation == DrawTessellation::Adaptive && draw.rule == AdaptiveRule::Screen,
             "adaptive screen-rule");
    only_for("outline_tolerance", draw.tessellation == DrawTessellation::Adaptive && draw.rule != AdaptiveRule::Screen,
             "adaptive silhouette- or contour-rule");
    if (dj.contains("pixels_per_segment"))
      draw.pixels_per_segment = r.number(dj["pixels_per_segment"], at + ".pixels_per_segment", 1e-3, 1e6);
    if (dj.contains("outline_tolerance"))
      draw.outline_tolerance = r.number(dj["outline_tolerance"], at + ".outline_tolerance", 1e-4, 1e6);
    if (!dj.contains("instances")) {
      draw.instances.push_back({});
    } else {
      const json& list = dj["instances"];
      if (!list.is_array() || list.empty()) r.fail(at + ".instances", "is not a non-empty list");
      for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string ai = at + ".instances[" + std::to_string(i) + "]";
        r.only_keys(list[i], ai, {"translate", "scale", "rotate_y_deg"});
        SceneInstance inst;
        if (list[i].contains("translate")) inst.translate = r.vec3(list[i]["translate"], ai + ".translate");
        if (list[i].contains("scale")) {
          const json& sj = list[i]["scale"];
          if (sj.is_array()) {
            inst.scale = r.vec3(sj, ai + ".scale");
            for (int k = 0; k < 3; ++k)
              if (!(inst.scale[k] >= 1e-6 && inst.scale[k] <= 1e6))
                r.fail(ai + ".scale", "each factor must be within 1e-6..1e6");
          } else {
            inst.scale = glm::dvec3(r.number(sj, ai + ".scale", 1e-6, 1e6));
          }
        }
        if (list[i].contains("rotate_y_deg"))
          inst.rotate_y_deg = r.number(list[i]["rotate_y_deg"], ai + ".rotate_y_deg", -1e6, 1e6);
        draw.instances.push_back(inst);
      }
    }
    scene.draws.push_back(std::move(draw));
  }
  for (std::size_t k = 0; k < j["camera_path"].size(); ++k) {
    const json& cj = j["camera_path"][k];
    const std::string at = "camera_path[" + std::to_string(k) + "]";
    r.only_keys(cj, at, {"eye", "target", "fov_deg"});
    if (!cj.contains("eye")) r.fail(at + ".eye", "is missing");
    SceneCamera cam;
    cam.eye = r.vec3(cj["eye"], at + ".eye");
    if (cj.contains("target")) cam.target = r.vec3(cj["target"], at + ".target");
    if (cj.contains("fov_deg")) cam.fov_deg = r.number(cj["fov_deg"], at + ".fov_deg", 1, 179);
    if (cam.eye == cam.target) r.fail(at, "eye and target coincide");
    scene.cameras.push_back(cam);
  }
  // Every mesh read now, so that a bad one stops the run before any frame.
  std::set<std::string> seen;
  for (std::size_t d = 0; d < scene.draws.size(); ++d) {
    if (!seen.insert(scene.draws[d].mesh).second) continue;
    try {
      (void)load_mesh(scene.draws[d].mesh);
    } catch (const InputError& e) {
      r.fail("draws[" + std::to_string(d) + "].mesh", e.what());
    }
  }
  return scene;
}

std::uint64_t untessellated_cycles(const UnitConfig& cfg, std::uint64_t vertices) {
  if (!cfg.ge_core()) return vertices * static_cast<std::uint64_t>(cfg.gpe_cycles);
  // Full waves of the core's own program (no shader work: nothing to evaluate or displace), in
  // the unit's cycles, rounded up once for the draw.
  const std::uint64_t lanes = static_cast<std::uint64_t>(cfg.ge_core_lanes);
  const std::uint64_t core_cycles = (vertices + lanes - 1) / lanes * core_wave_cycles(cfg.environment());
  return static_cast<std::uint64_t>(std::ceil(static_cast<double>(core_cycles) * cfg.unit_mhz / cfg.ge_core_mhz));
}

std::vector<FrameRun> run_scene(const Scene& scene, const UnitConfig& cfg,
                                const std::function<void(const FrameRun&)>& on_frame) {
  std::map<std::string, Mesh> meshes;
  for (const SceneDraw& draw : scene.draws)
    if (!meshes.count(draw.mesh)) meshes.emplace(draw.mesh, load_mesh(draw.mesh));
  // Each instance placed in the world once; the runs that do not depend on the camera, once.
  std::vector<std::vector<Mesh>> placed_meshes(scene.draws.size());
  std::map<std::pair<std::size_t, std::size_t>, DrawRun> fixed_runs;
  for (std::size_t d = 0; d < scene.draws.size(); ++d)
    for (const SceneInstance& inst : scene.draws[d].instances)
      placed_meshes[d].push_back(placed(meshes.at(scene.draws[d].mesh), inst));

  auto run_instance = [&](std::size_t d, std::size_t i, const SceneCamera& camera) {
    const SceneDraw& draw = scene.draws[d];
    const Mesh& mesh = placed_meshes[d][i];
    DrawRun run;
    run.draw = d;
    run.instance = i;
    run.triangles = mesh.triangle_count();
    if (draw.tessellation == DrawTessellation::None) {
      // The geometry engine runs its vertex work once per distinct vertex; the unit has none.
      run.vertices = mesh.vertex_count();
      run.cycles = untessellated_cycles(cfg, run.vertices);
      return run;
    }
    run.tessellated = true;
    UnitConfig c = cfg;
    std::optional<TessSettings> settings;
    if (draw.tessellation == DrawTessellation::Uniform) {
      c.tess_factor = draw.L;
    } else {
      settings.emplace();
      settings->kind = PatternKind::D3D11;
      settings->source = FactorSource::Adaptive;
      settings->rule = draw.rule;
      settings->camera = {camera.eye, camera.target, camera.fov_deg, scene.viewport_width, scene.viewport_height};
      settings->pixels_per_segment = draw.pixels_per_segment;
      settings->outline_tolerance = draw.outline_tolerance;
      validate(*settings, scene.source);
      bind_silhouette(*settings, mesh);
    }
    MeshPatterns patterns(settings ? &*settings : nullptr);
    const SimResult r = simulate(mesh, c, SimHooks{}, patterns);
    run.vertices = r.gpe.vertices;
    run.unit_cycles = r.run_cycles();
    run.cycles = r.run_cycles() + r.gpe_drain_cycles;
    return run;
  };

  std::vector<FrameRun> frames;
  for (std::size_t k = 0; k < scene.cameras.size(); ++k) {
    FrameRun frame;
    frame.frame = k;
    for (std::size_t d = 0; d < scene.draws.size(); ++d) {
      for (std::size_t i = 0; i < scene.draws[d].instances.size(); ++i) {
        DrawRun run;
        if (scene.draws[d].tessellation == DrawTessellation::Adaptive) {
          run = run_instance(d, i, scene.cameras[k]);
        } else {
          auto it = fixed_runs.find({d, i});
          if (it == fixed_runs.end()) it = fixed_runs.emplace(std::make_pair(d, i), run_instance(d, i, {})).first;
          run = it->second;
        }
        frame.cycles += run.cycles;
        frame.vertices += run.vertices;
        if (run.tessellated) frame.tessellated_vertices += run.vertices;
        else frame.unit_idle_cycles += run.cycles;
        frame.draws.push_back(run);
      }
    }
    if (on_frame) on_frame(frame);
    frames.push_back(std::move(frame));
  }
  return frames;
}

}  // namespace tessim::sim
