// Mesh import through Assimp. PLY and OFF files are checked structurally before Assimp sees
// them (model/io/format.hpp says why), and Assimp's error log is watched for the messages that
// mean geometry was altered.
#include "model/io/import.hpp"

#include <assimp/DefaultLogger.hpp>
#include <assimp/Importer.hpp>
#include <assimp/Logger.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>
#include <fstream>
#include <limits>
#include <sstream>
#include <mutex>

#include "model/io/format.hpp"
#include "model/io/ply.hpp"
#include "model/st_mesh.hpp"

namespace tessim::io {

namespace {

std::string read_file(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, "file", "cannot be opened for reading");
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(file, "file", "read error");
  return data;
}

// ---------------------------------------------------------------------------------------------
// Assimp's error log: some readers report altered geometry only there.

class ErrorCollector : public Assimp::Logger {
 public:
  explicit ErrorCollector(std::vector<std::string>* errors) : Logger(NORMAL), errors_(errors) {}
  void OnDebug(const char*) override {}
  void OnVerboseDebug(const char*) override {}
  void OnInfo(const char*) override {}
  void OnWarn(const char*) override {}
  void OnError(const char* message) override { errors_->emplace_back(message); }
  bool attachStream(Assimp::LogStream*, unsigned int) override { return false; }
  bool detachStream(Assimp::LogStream*, unsigned int) override { return false; }

 private:
  std::vector<std::string>* errors_;
};

// Logged errors that mean vertices or faces were dropped, clamped or invented. Other logged
// errors (missing materials or textures, ignored animation tracks) leave the geometry intact.
bool alters_geometry(const std::string& message) {
  const std::string lower = to_lower(message);
  for (const char* key : {"out of range", "incorrect", "not allowed", "aren't allowed", "truncat", "unexpected end"})
    if (lower.find(key) != std::string::npos) return true;
  return false;
}

// The DefaultLogger is a process-wide singleton: imports are serialized.
std::mutex& assimp_mutex() {
  static std::mutex m;
  return m;
}

// ---------------------------------------------------------------------------------------------
// The scene.

glm::dmat4 to_glm(const aiMatrix4x4& m) {
  // aiMatrix4x4 is row-major (a1..a4 is the first row); glm is column-major.
  return glm::dmat4(m.a1, m.b1, m.c1, m.d1, m.a2, m.b2, m.c2, m.d2, m.a3, m.b3, m.c3, m.d3, m.a4, m.b4, m.c4, m.d4);
}

struct MeshInstance {
  unsigned mesh = 0;
  glm::dmat4 transform{1.0};
};

void collect_instances(const aiNode* node, const glm::dmat4& parent, std::vector<MeshInstance>& out, int depth) {
  if (depth > 1024 || node == nullptr) return;  // a cyclic or absurdly deep node graph, a missing child
  const glm::dmat4 transform = parent * to_glm(node->mTransformation);
  if (node->mNumMeshes > 0 && node->mMeshes == nullptr) return;
  for (unsigned i = 0; i < node->mNumMeshes; ++i) out.push_back({node->mMeshes[i], transform});
  if (node->mNumChildren > 0 && node->mChildren == nullptr) return;
  for (unsigned c = 0; c < node->mNumChildren; ++c) collect_instances(node->mChildren[c], transform, out, depth + 1);
}

// "face 3", or "mesh 1 face 3" where the scene has several meshes.
std::string scene_element(bool several_meshes, unsigned mesh, const std::string& what) {
  return several_meshes ? "mesh " + std::to_string(mesh) + " " + what : what;
}

glm::dvec3 to_glm(const aiVector3D& v) { return glm::dvec3(v.x, v.y, v.z); }

std::string format_number(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

// Assimp holds coordinates in single precision (float32, 24-bit significand), whatever the
// file stores. Far from the origin the float32 grid is coarse: at 1e7 its step is 1. A mesh
// whose extent is not much larger than that step has lost its shape on import (vertices moved
// or merged, normals that then cancel out): refuse it, saying why, rather than tessellate
// what is left. The limit: the step at the largest coordinate of an axis must stay within
// kMaxRelativeStep of the mesh's extent (its largest bounding-box side).
constexpr double kMaxRelativeStep = 1.0 / 1024.0;

// The float32 step (unit in the last place) at magnitude `x`.
double float32_step(double x) {
  const float f = static_cast<float>(std::abs(x));
  return static_cast<double>(std::nextafter(f, std::numeric_limits<float>::infinity())) - static_cast<double>(f);
}

void check_precision(const std::string& file, const std::string& element, const glm::dvec3& lo, const glm::dvec3& hi,
                     std::vector<std::string>& warnings) {
  const glm::dvec3 size = hi - lo;
  const double extent = std::max({size.x, size.y, size.z});
  double magnitude = 0.0;
  int axis = 0;
  for (int a = 0; a < 3; ++a) {
    const double m = std::max(std::abs(lo[a]), std::abs(hi[a]));
    if (m > magnitude) {
      magnitude = m;
      axis = a;
    }
  }
  const double step = float32_step(magnitude);
  const std::string where = std::string(1, "xyz"[axis]) + " reaches " + format_number(magnitude) +
                            ", where single precision (float32, in which Assimp imports every file) resolves steps of " +
                            format_number(step);
  if (extent == 0.0) {
    // Every vertex at one point: a degenerate mesh, or one that the float32 grid collapsed.
    if (magnitude > 0.0)
      warnings.push_back(file + ": " + element + ": all vertices import at one position; " + where +
                         ": differences smaller than that in the file are lost");
    return;
  }
  if (step > kMaxRelativeStep * extent)
    throw InputError(file, element,
                     where + ", " + format_number(100.0 * step / extent) + " % of the mesh extent " +
                         format_number(extent) + ": the shape is lost on import (tessim needs steps below 1/1024 " +
                         "of the extent); move the mesh near the origin");
}

// Index and value checks on the scene as read, before triangulation touches it; the precision
// check of each mesh; faces of 1 or 2 vertices counted for a warning.
void check_scene(const std::string& file, const aiScene* scene, std::vector<std::string>& warnings) {
  const bool several = scene->mNumMeshes > 1;
  std::uint64_t small_faces = 0, triangles_or_polygons = 0;
  std::string first_small_face;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices >= 3) {
        ++triangles_or_polygons;
      } else if (face.mNumIndices > 0 && small_faces++ == 0) {
        first_small_face = scene_element(several, m, "face " + std::to_string(f));
      }
      // Names are built only for a message: this runs for every corner.
      auto face_element = [&] { return scene_element(several, m, "face " + std::to_string(f)); };
      if (face.mNumIndices == 0) throw InputError(file, face_element(), "has no vertices");
      for (unsigned i = 0; i < face.mNumIndices; ++i) {
        const unsigned v = face.mIndices[i];
        if (v >= mesh->mNumVertices)
          throw InputError(file, face_element(),
                           "vertex index " + std::to_string(v) + " out of range (" +
                               std::to_string(mesh->mNumVertices) + " vertices)");
        auto vertex_element = [&] { return scene_element(several, m, "vertex " + std::to_string(v)); };
        const glm::dvec3 p = to_glm(mesh->mVertices[v]);
        if (!is_finite(p)) throw InputError(file, vertex_element(), "coordinate is NaN or infinite " + format_vec(p));
        if (face.mNumIndices >= 3) {
          lo = glm::min(lo, p);
          hi = glm::max(hi, p);
        }
        if (mesh->mNormals) {
          const glm::dvec3 n = to_glm(mesh->mNormals[v]);
          if (!is_finite(n))
            throw InputError(file, vertex_element(), "normal in the file is NaN or infinite " + format_vec(n));
        }
      }
    }
    if (lo.x <= hi.x) check_precision(file, scene_element(several, m, "vertex coordinates"), lo, hi, warnings);
  }
  // Points and lines among surface faces: a file that mixes them, or faces that lost vertices.
  // Only triangles and polygons are tessellated; a file of nothing else is refused later.
  if (small_faces > 0 && triangles_or_polygons > 0)
    warnings.push_back(file + ": " + first_small_face + ": " + std::to_string(small_faces) +
                       (small_faces == 1 ? " face" : " faces") +
                       " of 1 or 2 vertices (points or lines) ignored; only triangles and polygons are tessellated");
}

// Tags are read from the file by vertex index (read_ply_tags); Assimp's PLY reader keeps the
// file's vertices in order, one mesh of them. Should it ever not (a reader change, per-face
// data it splits vertices for), tags would land on the wrong vertices: refuse instead.
bool same_float(float a, float b) {
  // Within a few units in the last place: Assimp parses ASCII numbers with its own routine,
  // which is not always correctly rounded.
  if (a == b) return true;
  if (std::signbit(a) != std::signbit(b)) return false;
  const auto ia = std::bit_cast<std::int32_t>(a), ib = std::bit_cast<std::int32_t>(b);
  return std::abs(static_cast<std::int64_t>(ia) - static_cast<std::int64_t>(ib)) <= 4;
}

void check_tag_order(const std::string& file, const aiScene* scene, const PlyTags& tags) {
  auto refuse = [&](const std::string& why) {
    return InputError(file, "vertex tags", "cannot be matched with the vertices Assimp read (" + why + ")");
  };
  if (scene->mNumMeshes != 1) throw refuse(std::to_string(scene->mNumMeshes) + " meshes");
  const aiMesh* mesh = scene->mMeshes[0];
  if (mesh->mNumVertices != tags.positions.size())
    throw refuse(std::to_string(mesh->mNumVertices) + " vertices for the file's " + std::to_string(tags.positions.size()));
  for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
    const aiVector3D& a = mesh->mVertices[v];
    const glm::vec3& p = tags.positions[v];
    if (!same_float(a.x, p.x) || !same_float(a.y, p.y) || !same_float(a.z, p.z))
      throw refuse("vertex " + std::to_string(v) + " is not where the file puts it");
  }
}

}  // namespace

std::string ImportedMesh::vertex_name(std::uint32_t vertex) const {
  return scene_element(several_meshes, origin[vertex].first, "vertex " + std::to_string(origin[vertex].second));
}

ImportedMesh import_mesh(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(file, "file", "does not exist");
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(file, "file", "is not a regular file");
  const std::string ext = lower_extension(path);
  if (std::filesystem::file_size(path, ec) == 0 && !ec) throw InputError(file, "file", "is empty");
  std::optional<PlyTags> ply_tags;
  if (ext == ".ply") {
    const std::string data = read_file(file);
    check_ply(file, data);
    ply_tags = read_ply_tags(file, data);
  }
  if (ext == ".off") check_off(file, read_file(file));
  if (ext == ".stl") check_stl(file, read_file(file));
  if (ext == ".obj") {
    if (auto located = find_bad_obj_face(file, read_file(file))) throw *located;
  }

  std::lock_guard<std::mutex> lock(assimp_mutex());
  std::vector<std::string> logged_errors;
  Assimp::DefaultLogger::set(new ErrorCollector(&logged_errors));
  struct LoggerReset {
    ~LoggerReset() { Assimp::DefaultLogger::set(nullptr); }
  } logger_reset;

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(file, 0);
  if (!scene) {
    throw InputError(file, "import", std::string("Assimp cannot read it: ") + importer.GetErrorString());
  }
  for (const std::string& message : logged_errors)
    if (alters_geometry(message)) throw InputError(file, "import", "Assimp reported: " + message);
  if (scene->mNumMeshes == 0 || !scene->mRootNode) throw InputError(file, "faces", "the file contains no mesh");

  ImportedMesh out;
  check_scene(file, scene, out.warnings);
  scene = importer.ApplyPostProcessing(aiProcess_Triangulate);
  if (!scene) throw InputError(file, "import", std::string("Assimp cannot triangulate it: ") + importer.GetErrorString());

  std::vector<MeshInstance> instances;
  collect_instances(scene->mRootNode, glm::dmat4(1.0), instances, 0);
  for (const MeshInstance& inst : instances)
    if (inst.mesh >= scene->mNumMeshes)
      throw InputError(file, "node graph",
                       "refers to mesh " + std::to_string(inst.mesh) + " of " + std::to_string(scene->mNumMeshes));
  // Readers that build no node graph for their meshes: take every mesh as it is.
  if (instances.empty())
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) instances.push_back({m, glm::dmat4(1.0)});

  // STL stores one facet normal per triangle (often zero or rounded), not vertex normals:
  // vertex normals are computed from the geometry instead.
  bool use_file_normals = ext != ".stl";
  std::size_t vertices = 0, points = 0, lines = 0, triangle_faces = 0;
  for (const MeshInstance& inst : instances) {
    const aiMesh* mesh = scene->mMeshes[inst.mesh];
    vertices += mesh->mNumVertices;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const unsigned n = mesh->mFaces[f].mNumIndices;
      if (n == 1) ++points;
      else if (n == 2) ++lines;
      else if (n == 3) ++triangle_faces;
    }
    if (!mesh->mNormals) use_file_normals = false;
  }
  if (triangle_faces == 0)
    throw InputError(file, "faces",
                     "no triangles (" + std::to_string(vertices) + " vertices, " + std::to_string(points) +
                         " point and " + std::to_string(lines) + " line primitives)");

  if (ply_tags) check_tag_order(file, scene, *ply_tags);

  out.several_meshes = scene->mNumMeshes > 1;
  out.mesh.source = file;
  out.mesh.normals_from_file = use_file_normals;
  std::vector<glm::dvec3>& positions = out.mesh.positions;
  // Upper bounds (vertices no triangle uses are left out): no regrowth of large arrays.
  positions.reserve(vertices);
  out.mesh.triangles.reserve(triangle_faces);
  const bool keep_origin = use_file_normals || ply_tags;
  if (use_file_normals) out.mesh.normals.reserve(vertices);
  if (keep_origin) out.origin.reserve(vertices);
  if (ply_tags) out.mesh.tags.reserve(vertices);
  for (const MeshInstance& inst : instances) {
    const aiMesh* mesh = scene->mMeshes[inst.mesh];
    const glm::dmat3 linear(inst.transform);
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(linear));
    // A mirroring transform reverses the winding in world space; swap to keep faces outward.
    const bool mirrored = glm::determinant(linear) < 0.0;
    std::vector<std::uint32_t> remap(mesh->mNumVertices, std::numeric_limits<std::uint32_t>::max());
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      glm::uvec3 tri;
      for (int c = 0; c < 3; ++c) {
        const unsigned v = face.mIndices[c];
        if (remap[v] == std::numeric_limits<std::uint32_t>::max()) {
          const aiVector3D& a = mesh->mVertices[v];
          const glm::dvec3 p = glm::dvec3(inst.transform * glm::dvec4(a.x, a.y, a.z, 1.0));
          if (!is_finite(p))
            throw InputError(file, scene_element(out.several_meshes, inst.mesh, "vertex " + std::to_string(v)),
                             "position is not finite after the node transform " + format_vec(p));
          // Welding comes later; until then every instance vertex needs its own 32-bit index.
          if (positions.size() >= std::numeric_limits<std::uint32_t>::max())
            throw InputError(file, "vertices", "more than 2^32 - 1 vertices before welding");
          remap[v] = static_cast<std::uint32_t>(positions.size());
          positions.push_back(p);
          // Only weld()'s messages about file normals or tags name vertices.
          if (use_file_normals) out.mesh.normals.push_back(normal_matrix * to_glm(mesh->mNormals[v]));
          if (keep_origin) out.origin.emplace_back(inst.mesh, v);
          if (ply_tags) {
            // check_tag_order: Assimp's vertex v is the file's vertex v.
            const VertexTags& tags = ply_tags->tags[v];
            if (const auto problem = tag_value_problem(tags))
              throw InputError(file, scene_element(out.several_meshes, inst.mesh, "vertex " + std::to_string(v)), *problem);
            out.mesh.tags.push_back(tags);
          }
        }
        tri[c] = remap[v];
      }
      if (mirrored) std::swap(tri[1], tri[2]);
      out.mesh.triangles.push_back(tri);
    }
  }
  return out;
}

}  // namespace tessim::io
