// A frame, not a mesh (docs/scenes.md): a scene is a list of draws — a mesh, its instances, and
// how it is tessellated: the uniform pattern, an adaptive rule from the frame's camera, or not at
// all — and a camera path. Every frame runs its draws in order through one unit and its
// geometry engine; each instance of a tessellated draw runs from an empty unit to the geometry
// engine's last vertex (fill and drain per instance, as a GPU that does not overlap draws), and
// an untessellated instance costs the geometry engine K cycles per distinct vertex while the
// unit idles.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "model/factors.hpp"
#include "sim/config/config.hpp"

namespace tessim::sim {

enum class DrawTessellation { None, Uniform, Adaptive };

// World placement of one instance: scaled (per axis), rotated about +Y, then translated.
struct SceneInstance {
  glm::dvec3 translate{0.0};
  glm::dvec3 scale{1.0};
  double rotate_y_deg = 0.0;
};

struct SceneDraw {
  std::string name;
  std::string mesh;  // as resolved: relative paths against the scene file's folder
  std::vector<SceneInstance> instances;
  DrawTessellation tessellation = DrawTessellation::Uniform;
  int L = 4;                                 // uniform
  AdaptiveRule rule = AdaptiveRule::Screen;  // adaptive: screen, silhouette or contour
  double pixels_per_segment = 16.0;
  double outline_tolerance = 0.5;
};

struct SceneCamera {
  glm::dvec3 eye{0.0, 0.0, 5.0};
  glm::dvec3 target{0.0};
  double fov_deg = 45.0;
};

struct Scene {
  std::string source;  // the scene file, for messages
  std::vector<SceneDraw> draws;
  std::vector<SceneCamera> cameras;  // one frame each
  int viewport_width = 1280, viewport_height = 720;
  double clock_mhz = 0.0;  // the unit's clock for frame times in ms; 0: not stated
};

// Reads a scene file (docs/scenes.md); InputError(file, element, reason) for anything malformed,
// a mesh that cannot be read included (meshes are loaded to check them).
Scene load_scene(const std::string& path);

struct DrawRun {
  std::size_t draw = 0, instance = 0;
  bool tessellated = false;
  std::uint64_t triangles = 0;    // input triangles of the instance
  std::uint64_t vertices = 0;     // vertices the geometry engine processed
  std::uint64_t cycles = 0;       // from the draw's start to the geometry engine's last vertex finished
  std::uint64_t unit_cycles = 0;  // from the start to the unit's last vertex taken: 0 for an untessellated draw
};

struct FrameRun {
  std::size_t frame = 0;
  std::uint64_t cycles = 0;            // the frame: its draws one after another
  std::uint64_t unit_idle_cycles = 0;  // the frame's untessellated draws, when the unit has no work
  std::uint64_t vertices = 0;
  std::uint64_t tessellated_vertices = 0;
  std::vector<DrawRun> draws;
};

// Unit cycles the geometry engine of `cfg` spends on `vertices` untessellated vertices: K each,
// or a shader core's full waves of its own program.
std::uint64_t untessellated_cycles(const UnitConfig& cfg, std::uint64_t vertices);

// Runs every frame of the scene through a unit of configuration `cfg` (its tess_factor is
// replaced by each draw's L). Instances whose work does not depend on the camera (uniform and
// untessellated draws) are simulated once and reused: the unit is deterministic. `on_frame`
// sees each frame as it completes.
std::vector<FrameRun> run_scene(const Scene& scene, const UnitConfig& cfg,
                                const std::function<void(const FrameRun&)>& on_frame = {});

}  // namespace tessim::sim
