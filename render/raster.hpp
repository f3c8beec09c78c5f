// A small software rasterizer for looking at meshes and tessellations: perspective camera framed
// automatically on the geometry, z-buffer, per-pixel Phong shading of interpolated vertex
// normals, two-sided lighting (meshes with inconsistent winding still shade correctly),
// optional wireframe overlay and 2x2 supersampling. Images are written as PNG (8-bit sRGB) or
// OpenEXR (half-float linear) through OpenImageIO, all-or-nothing.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace tessim::render {

// Triangles to draw: one normal per position (need not be unit length). Winding may be
// inconsistent. edge_flags is optional (empty: every edge is a primary edge); bit e of
// edge_flags[t] marks the edge from corner e to corner (e+1)%3 of triangle t as primary
// (drawn darker in the wireframe, e.g. the boundary of a tessellated patch); unmarked edges
// are secondary (drawn lighter, e.g. edges inside a patch). scalars is optional (empty: the
// albedo colour everywhere); with one value per position the surface is coloured by the value,
// interpolated per pixel and mapped through RenderOptions::scalar_lo..scalar_hi to viridis
// (a heat map, e.g. of errors). wire_colours is optional (empty: RenderOptions::wire_colour);
// with one colour per triangle the wireframe draws that triangle's edges in it (e.g. coloured by
// the tessellation factor of the patch the triangle belongs to).
struct RenderMesh {
  std::vector<glm::dvec3> positions;
  std::vector<glm::dvec3> normals;
  std::vector<glm::uvec3> triangles;
  std::vector<std::uint8_t> edge_flags;
  std::vector<double> scalars;
  std::vector<glm::dvec3> wire_colours;
};

// Checks that every index is in range and the arrays agree in size; throws InputError.
void validate(const RenderMesh& mesh, std::string_view what);

enum class UpAxis { Y, Z };

struct ViewAngles {
  double azimuth_deg = 35.0;    // around the up axis, from the front (+Z for Y-up, -Y for Z-up) towards +X
  double elevation_deg = 25.0;  // above the horizontal plane, in [-90, 90]
  UpAxis up = UpAxis::Y;
};

struct Camera {
  glm::dvec3 eye{0.0, 0.0, 1.0};
  glm::dvec3 target{0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fov_y_deg = 30.0;
  double aspect = 1.0;  // width / height
};

// A camera looking from the given angles that frames all `points` (typically the vertices of
// every mesh that will be drawn with it) inside the image with a small margin, centred.
// Throws InputError for an elevation outside [-90, 90] or non-finite angles.
Camera frame_camera(std::span<const glm::dvec3> points, const ViewAngles& view, int width, int height,
                    double fov_y_deg = 30.0);

struct RenderOptions {
  int width = 1024;
  int height = 768;
  bool supersample = true;   // 2x2 samples per pixel, box-filtered
  bool wireframe = false;
  double wire_width_px = 1.0;          // primary edges, in output pixels
  glm::dvec3 albedo{0.42, 0.50, 0.66};  // soft blue
  glm::dvec3 background{0.94, 0.94, 0.93};
  glm::dvec3 wire_colour{0.10, 0.12, 0.16};
  double wire_opacity = 0.8;            // primary edges; secondary edges get 40% of it
  // Key light direction in view space (x right, y up, z towards the viewer): upper left front.
  glm::dvec3 light_in_view{-0.70, 0.60, 0.38};
  double ambient = 0.16;
  double diffuse = 0.82;
  double specular = 0.25;
  double shininess = 40.0;
  // Heat maps (RenderMesh::scalars): the value range mapped to the colour map's ends. The
  // lighting is softened (less contrast, no highlight) so that the colour stays readable.
  double scalar_lo = 0.0, scalar_hi = 1.0;
};

// Throws InputError unless 1 <= width, height <= kMaxImageSide.
constexpr int kMaxImageSide = 8192;
void validate(const RenderOptions& options);

// Linear RGB, row-major, top row first.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;  // width * height * 3

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 0.0f) {}
  float* pixel(int x, int y) { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
  const float* pixel(int x, int y) const { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
};

// What a picture shows of the surface's shape, at the renderer's sample resolution (its width x
// height, twice that with supersampling), for measuring outlines: the visible contour samples
// (covered samples with a 4-neighbour that is background or farther in view depth by more than a
// jump: the outer outline and every interior occluding contour, such as a leg in front of the
// body; the image border is not a contour) and the coverage as runs of covered samples per row.
struct ContourMap {
  int width = 0, height = 0;
  std::vector<std::uint32_t> contour;   // x, y of each contour sample, row by row
  std::vector<std::uint32_t> coverage;  // y, x_begin, x_end (exclusive) of each run of covered samples
};

// Renders one mesh, which must outlive the renderer (it is referenced, not copied). Rows are
// rasterized in bands, so memory beyond the mesh and the returned rows is bounded by the band
// size whatever the image size.
class Renderer {
 public:
  Renderer(const RenderMesh& mesh, const Camera& camera, const RenderOptions& options);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Output rows [y_begin, y_end) as an image of options.width x (y_end - y_begin).
  Image render_rows(int y_begin, int y_end) const;
  Image render() const { return render_rows(0, height()); }
  int width() const;
  int height() const;
  // The contours and coverage (ContourMap); `depth_jump` in the mesh's units, > 0.
  ContourMap contours(double depth_jump) const;
  // How much of the mesh's detail the view shows (for choosing a view): over the visible
  // samples, the sum of their triangle's density, mean triangle area / its area (capped at 100).
  double visible_detail() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The model's best side: of eight azimuths 45 degrees apart (starting at the default) at the
// default elevation, the one that shows most detail (Renderer::visible_detail: small triangles
// seen face-on weigh most). Where a model has its detail (a face, a front panel), it has its
// small triangles, so this finds the side a person would show without knowing which way the
// model faces.
ViewAngles best_view(const RenderMesh& mesh, UpAxis up);

// Renders the whole image in one call.
Image render(const RenderMesh& mesh, const Camera& camera, const RenderOptions& options);

// Two panels of equal height next to each other, separated by a plain vertical bar.
constexpr int kSeparatorWidth = 6;
Image side_by_side(const Image& left, const Image& right, const glm::dvec3& separator_colour);

// True for .png and .exr (any case): the formats write_image and ImageFileWriter accept; and for
// outputs written directly (standard output "-", a device, a pipe), which get PNG.
bool is_supported_image(const std::filesystem::path& path);

// Streams an image to a PNG or EXR file band by band; nothing appears at `path` until
// finish() succeeds. The constructor throws InputError for an unsupported extension or an
// output that cannot be opened.
class ImageFileWriter {
 public:
  ImageFileWriter(const std::filesystem::path& path, int width, int height);
  ~ImageFileWriter();
  ImageFileWriter(const ImageFileWriter&) = delete;
  ImageFileWriter& operator=(const ImageFileWriter&) = delete;

  void write_rows(const Image& band);  // the next band.height rows, full width
  void finish();                       // all rows written: close and move into place

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

void write_image(const Image& image, const std::filesystem::path& path);

}  // namespace tessim::render
