// Streamed export of tessellated meshes: binary little-endian PLY or ASCII OBJ
// (MeshWriter in model/mesh_io.hpp); whole meshes, tags included, as PLY (write_ply).
#include <bit>
#include <charconv>
#include <cstring>
#include <iostream>
#include <optional>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "model/base/output_file.hpp"
#include "model/io/format.hpp"
#include "model/io/ply.hpp"
#include "model/mesh_io.hpp"
#include "model/pattern.hpp"

namespace tessim {

namespace {

static_assert(std::endian::native == std::endian::little,
              "the PLY writer stores native doubles and uint32 as binary_little_endian");

void append_number(std::string& s, double x) {
  char buf[32];
  // Shortest representation that reads back as the same double.
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, x);
  s.append(buf, ec == std::errc() ? ptr : buf);
}

// An OBJ line "<keyword> x y z\n".
void append_obj_vec(std::string& s, const char* keyword, const glm::dvec3& v) {
  s += keyword;
  for (int i = 0; i < 3; ++i) {
    s += ' ';
    append_number(s, v[i]);
  }
  s += '\n';
}

void append_raw(std::string& s, const void* data, std::size_t size) { s.append(static_cast<const char*>(data), size); }

// Extends s by n bytes and returns where they start: records are then copied in place, without
// a capacity check per field.
char* extend(std::string& s, std::size_t n) {
  const std::size_t at = s.size();
  s.resize(at + n);
  return s.data() + at;
}

static_assert(sizeof(glm::dvec3) == 3 * sizeof(double), "a PLY vertex record is two dvec3 back to back");
constexpr std::size_t kPlyVertexBytes = 6 * sizeof(double);
constexpr std::size_t kPlyFaceBytes = 1 + 3 * sizeof(std::uint32_t);  // uchar 3, three uint indices

// One PLY face record: the corner count, then the indices (unaligned, little-endian).
char* put_face(char* out, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  const std::uint32_t indices[3] = {a, b, c};
  *out = 3;
  std::memcpy(out + 1, indices, sizeof indices);
  return out + kPlyFaceBytes;
}

}  // namespace

bool is_supported_output(const std::filesystem::path& path) {
  const std::string ext = io::lower_extension(path);
  // Standard output, a device or a pipe needs no extension: it gets binary PLY.
  return ext == ".ply" || ext == ".obj" || output_kind(path) != OutputKind::File;
}

struct MeshWriter::Impl {
  Impl(const std::filesystem::path& target, bool ply, std::uint64_t vertices, std::uint64_t triangles)
      : path(target), is_ply(ply), total_vertices(vertices), total_triangles(triangles) {
    file.emplace(target, ply);
    stream = &file->stream();
    buffer.reserve(2 * kBlock);  // a block and the patch that completes it: no reallocation
  }

  std::filesystem::path path;
  bool is_ply;
  std::optional<AtomicOutput> file;
  std::ostream* stream = nullptr;
  std::uint64_t total_vertices;
  std::uint64_t total_triangles;
  std::uint64_t vertices = 0;
  std::uint64_t triangles = 0;
  bool finished = false;
  // PLY keeps all faces after all vertices. A uniform patch's faces follow from its factor, so
  // only the sequence of factors is kept (run-length coded) and its faces are generated in
  // finish(); other patches keep their faces (global indices) in explicit_faces, and a run of
  // factor 0 stands for `count` such patches holding `vertices` vertices.
  struct Run {
    int L;
    std::uint64_t count;
    std::uint64_t vertices;  // factor 0: the vertices of the run's patches
    std::uint64_t faces;     // factor 0: the triangles of the run's patches
  };
  std::vector<Run> runs;
  std::vector<std::uint32_t> explicit_faces;
  int uniform_L = 0;  // the factor whose faces uniform_indices holds
  std::vector<std::uint32_t> uniform_indices;
  std::string buffer;

  static constexpr std::size_t kBlock = std::size_t{1} << 20;

  void write_buffer() {
    stream->write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    buffer.clear();
    if (!*stream) throw InputError(output_name(path), "output", "write failed");
  }
};

MeshWriter::MeshWriter(const std::filesystem::path& path, std::uint64_t total_vertices, std::uint64_t total_triangles) {
  if (!is_supported_output(path))
    throw InputError(path.string(), "output", "unsupported extension '" + path.extension().string() + "' (use .ply or .obj)");
  const bool ply = io::lower_extension(path) != ".obj";
  if (ply && total_vertices > std::numeric_limits<std::uint32_t>::max())
    throw InputError(path.string(), "output", std::to_string(total_vertices) + " vertices do not fit PLY's 32-bit indices");
  impl_ = std::make_unique<Impl>(path, ply, total_vertices, total_triangles);
  std::string& h = impl_->buffer;
  if (ply) {
    h += "ply\nformat binary_little_endian 1.0\ncomment tessim tessellated mesh\n";
    h += "element vertex " + std::to_string(total_vertices) + "\n";
    for (const char* p : {"x", "y", "z", "nx", "ny", "nz"}) h += std::string("property double ") + p + "\n";
    h += "element face " + std::to_string(total_triangles) + "\n";
    h += "property list uchar uint vertex_indices\nend_header\n";
  } else {
    h += "# tessim tessellated mesh: " + std::to_string(total_vertices) + " vertices, " +
         std::to_string(total_triangles) + " triangles\n";
  }
  impl_->write_buffer();
}

MeshWriter::~MeshWriter() = default;

void MeshWriter::add_patch(int L, const glm::dvec3* positions, const glm::dvec3* normals) {
  if (L < 1 || L > kMaxTessFactor) throw std::logic_error("MeshWriter::add_patch: factor " + std::to_string(L) + " out of range");
  const auto n = static_cast<std::size_t>(pattern_vertex_count(L));
  Impl& w = *impl_;
  if (w.uniform_L != L) {  // the flat index list of the last factor, for OBJ faces
    w.uniform_L = L;
    w.uniform_indices.clear();
    for (const glm::uvec3& t : pattern_triangles(L)) w.uniform_indices.insert(w.uniform_indices.end(), {t.x, t.y, t.z});
  }
  append(L, {positions, n}, {normals, n}, w.uniform_indices);
}

void MeshWriter::add_patch(std::span<const glm::dvec3> positions, std::span<const glm::dvec3> normals,
                           std::span<const std::uint32_t> indices) {
  for (std::uint32_t i : indices)
    if (i >= positions.size()) throw std::logic_error("MeshWriter::add_patch: index " + std::to_string(i) + " out of range");
  append(0, positions, normals, indices);
}

void MeshWriter::append(int L, std::span<const glm::dvec3> positions, std::span<const glm::dvec3> normals,
                        std::span<const std::uint32_t> indices) {
  Impl& w = *impl_;
  if (w.finished) throw std::logic_error("MeshWriter::add_patch after finish()");
  const std::uint64_t n = positions.size(), t = indices.size() / 3;
  if (normals.size() != n || indices.size() % 3 != 0)
    throw std::logic_error("MeshWriter::add_patch: mismatched positions, normals and indices");
  if (w.vertices + n > w.total_vertices || w.triangles + t > w.total_triangles)
    throw std::logic_error("MeshWriter::add_patch: more than the declared " + std::to_string(w.total_vertices) +
                           " vertices / " + std::to_string(w.total_triangles) + " triangles");

  std::string& s = w.buffer;
  if (w.is_ply) {
    char* out = extend(s, n * kPlyVertexBytes);
    for (std::uint64_t i = 0; i < n; ++i, out += kPlyVertexBytes) {
      std::memcpy(out, &positions[i], sizeof(glm::dvec3));
      std::memcpy(out + sizeof(glm::dvec3), &normals[i], sizeof(glm::dvec3));
    }
    // Faces come after all vertices: a uniform patch is remembered by its factor, any other
    // by its faces.
    if (w.runs.empty() || w.runs.back().L != L) w.runs.push_back({L, 0, 0, 0});
    Impl::Run& run = w.runs.back();
    ++run.count;
    if (L == 0) {
      run.vertices += n;
      run.faces += t;
      for (std::uint32_t i : indices) w.explicit_faces.push_back(static_cast<std::uint32_t>(w.vertices + i));
    }
  } else {
    for (std::uint64_t i = 0; i < n; ++i) {
      append_obj_vec(s, "v", positions[i]);
      append_obj_vec(s, "vn", normals[i]);
    }
    for (std::uint64_t f = 0; f < t; ++f) {
      s += 'f';
      for (std::uint64_t c = 0; c < 3; ++c) {
        const std::string index = std::to_string(w.vertices + indices[3 * f + c] + 1);  // OBJ counts from 1
        s += ' ';
        s += index;
        s += "//";
        s += index;
      }
      s += '\n';
    }
  }
  w.vertices += n;
  w.triangles += t;
  if (w.buffer.size() >= Impl::kBlock) w.write_buffer();  // large blocks: one system call per MiB
}

void MeshWriter::finish() {
  Impl& w = *impl_;
  if (w.finished) throw std::logic_error("MeshWriter::finish called twice");
  if (w.vertices != w.total_vertices || w.triangles != w.total_triangles)
    throw std::logic_error("MeshWriter::finish: " + std::to_string(w.vertices) + " of " + std::to_string(w.total_vertices) +
                           " vertices and " + std::to_string(w.triangles) + " of " + std::to_string(w.total_triangles) +
                           " triangles were written");
  if (w.is_ply) {
    std::uint32_t base = 0;
    std::size_t next_explicit = 0;
    for (const Impl::Run& run : w.runs) {
      if (run.L == 0) {
        for (std::uint64_t t = 0; t < run.faces; ++t, next_explicit += 3) {
          const std::uint32_t* f = &w.explicit_faces[next_explicit];
          put_face(extend(w.buffer, kPlyFaceBytes), f[0], f[1], f[2]);
          if (w.buffer.size() >= Impl::kBlock) w.write_buffer();
        }
        base += static_cast<std::uint32_t>(run.vertices);
        continue;
      }
      const int L = run.L;
      const std::uint64_t count = run.count;
      const std::vector<glm::uvec3> pattern = pattern_triangles(L);
      const auto patch_vertices = static_cast<std::uint32_t>(pattern_vertex_count(L));
      for (std::uint64_t p = 0; p < count; ++p) {
        char* out = extend(w.buffer, pattern.size() * kPlyFaceBytes);
        for (const glm::uvec3& tri : pattern) out = put_face(out, base + tri[0], base + tri[1], base + tri[2]);
        base += patch_vertices;
        if (w.buffer.size() >= Impl::kBlock) w.write_buffer();
      }
    }
  }
  w.write_buffer();
  w.file->commit();
  w.finished = true;
}

}  // namespace tessim

namespace tessim {

void write_ply(const Mesh& mesh, const std::filesystem::path& path) {
  const std::size_t n = mesh.positions.size();
  if (mesh.normals.size() != n || (mesh.has_tags() && mesh.tags.size() != n))
    throw std::logic_error("write_ply: " + std::to_string(n) + " positions, " + std::to_string(mesh.normals.size()) +
                           " normals, " + std::to_string(mesh.tags.size()) + " tag sets");
  AtomicOutput out(path, true);
  std::string buffer;
  auto flush = [&] {
    out.stream().write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    buffer.clear();
    if (!out.stream()) throw InputError(path.string(), "output", "write failed");
  };
  constexpr std::size_t kBlock = std::size_t{1} << 20;

  buffer += "ply\nformat binary_little_endian 1.0\n";
  buffer += mesh.has_tags() ? "comment tessim scalar-tagged mesh (docs/stpn.md)\n" : "comment tessim mesh\n";
  buffer += "element vertex " + std::to_string(n) + "\n";
  for (const char* p : {"x", "y", "z", "nx", "ny", "nz"}) buffer += std::string("property double ") + p + "\n";
  if (mesh.has_tags())
    for (const char* p : io::kPlyTagProperties) buffer += std::string("property double ") + p + "\n";
  buffer += "element face " + std::to_string(mesh.triangles.size()) + "\n";
  buffer += "property list uchar uint vertex_indices\nend_header\n";

  for (std::size_t v = 0; v < n; ++v) {
    const glm::dvec3& p = mesh.positions[v];
    const glm::dvec3& nv = mesh.normals[v];
    const double record[6] = {p.x, p.y, p.z, nv.x, nv.y, nv.z};
    append_raw(buffer, record, sizeof record);
    if (mesh.has_tags()) {
      const VertexTags& t = mesh.tags[v];
      const double tags[6] = {t.delta.x, t.delta.y, t.delta.z, t.sigma, t.theta, t.beta};
      append_raw(buffer, tags, sizeof tags);
    }
    if (buffer.size() >= kBlock) flush();
  }
  for (const glm::uvec3& t : mesh.triangles) {
    put_face(extend(buffer, kPlyFaceBytes), t.x, t.y, t.z);
    if (buffer.size() >= kBlock) flush();
  }
  flush();
  out.commit();
}

}  // namespace tessim
