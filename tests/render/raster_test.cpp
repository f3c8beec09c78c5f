// The software rasterizer behind `tessim render`: coverage, depth, lighting, wireframe, image
// files. The render subcommand end to end: tests/cli/render_cli_test.cpp.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "model/base/error.hpp"
#include "render/raster.hpp"
#include "tests/support/icosphere.hpp"
#include "tests/support/read_image.hpp"

namespace fs = std::filesystem;
using tessim::InputError;
using namespace tessim::render;
using tessim::testing::read_back;
using tessim::testing::ReadBack;

namespace {

constexpr double kPi = 3.14159265358979323846;

using tessim::render::test_meshes::icosphere;

double luminance(const float* rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

bool is_background(const float* rgb, const RenderOptions& options) {
  for (int k = 0; k < 3; ++k)
    if (std::abs(rgb[k] - options.background[k]) > 1e-6) return false;
  return true;
}

std::size_t count_covered(const Image& image, const RenderOptions& options) {
  std::size_t covered = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) covered += !is_background(image.pixel(x, y), options);
  return covered;
}

double max_difference(const Image& a, const Image& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) worst = std::max(worst, double(std::abs(a.rgb[i] - b.rgb[i])));
  return worst;
}

// Camera basis as the renderer defines it.
struct Basis {
  glm::dvec3 forward, right, up;
};
Basis basis(const Camera& camera) {
  Basis b;
  b.forward = glm::normalize(camera.target - camera.eye);
  b.right = glm::normalize(glm::cross(b.forward, camera.up));
  b.up = glm::cross(b.right, b.forward);
  return b;
}

// A scratch directory, removed afterwards.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("tessim_raster_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }
  std::vector<fs::path> entries() const {
    std::vector<fs::path> out;
    for (const auto& e : fs::directory_iterator(path_)) out.push_back(e.path().filename());
    return out;
  }

 private:
  fs::path path_;
};

Image constant_image(int w, int h, float value) {
  Image image(w, h);
  std::fill(image.rgb.begin(), image.rgb.end(), value);
  return image;
}

}  // namespace

TEST(Raster, SphereCoversItsProjectedDisc) {
  const RenderMesh sphere = icosphere(4);
  RenderOptions options;
  options.width = 400;
  options.height = 300;
  options.supersample = false;  // count whole pixels
  const Camera camera = frame_camera(sphere.positions, ViewAngles{}, options.width, options.height);
  // Framing a sphere centred at the origin keeps the target at its centre.
  ASSERT_LT(glm::length(camera.target), 1e-3);

  const Image image = render(sphere, camera, options);
  const double distance = glm::length(camera.eye - camera.target);
  // Silhouette cone half-angle asin(r/D); its image is a disc of radius tan(alpha) in the
  // normalized image plane.
  const double tan_alpha = std::tan(std::asin(1.0 / distance));
  const double tan_v = std::tan(0.5 * camera.fov_y_deg * kPi / 180.0);
  const double radius_px = tan_alpha / tan_v * 0.5 * options.height;
  const double expected = kPi * radius_px * radius_px;
  // One pixel along the rim either way, plus the polygonal sphere's slightly smaller silhouette.
  const double tolerance = 2.0 * kPi * radius_px + 0.01 * expected;
  const double covered = static_cast<double>(count_covered(image, options));
  EXPECT_NEAR(covered, expected, tolerance) << "radius " << radius_px << " px";
  // The framing leaves an 8% margin on the tighter (vertical) side.
  EXPECT_NEAR(radius_px, 0.92 * 0.5 * options.height, 0.02 * radius_px);
  // Nothing drawn in the corners.
  EXPECT_TRUE(is_background(image.pixel(0, 0), options));
  EXPECT_TRUE(is_background(image.pixel(options.width - 1, options.height - 1), options));
}

TEST(Raster, ZBufferKeepsTheNearerTriangle) {
  Camera camera;  // looking down -Z from +5
  camera.eye = {0, 0, 5};
  camera.target = {0, 0, 0};
  camera.up = {0, 1, 0};
  camera.aspect = 1.0;
  RenderOptions options;
  options.width = options.height = 64;

  // Same footprint around the image centre, at depths 0 (far) and 1 (near); their normals
  // differ so that the two shade differently.
  const glm::dvec3 toward_light = glm::normalize(options.light_in_view);
  auto triangle = [](double z, glm::dvec3 normal) {
    RenderMesh m;
    m.positions = {{-1, -1, z}, {1, -1, z}, {0, 1, z}};
    m.normals = {normal, normal, normal};
    m.triangles = {{0, 1, 2}};
    return m;
  };
  const RenderMesh near = triangle(1.0, toward_light), far = triangle(0.0, {0, 0, 1});
  auto both = [](const RenderMesh& first, const RenderMesh& second) {
    RenderMesh m = first;
    m.positions.insert(m.positions.end(), second.positions.begin(), second.positions.end());
    m.normals.insert(m.normals.end(), second.normals.begin(), second.normals.end());
    m.triangles.push_back(second.triangles[0] + glm::uvec3(3));
    return m;
  };
  const Image near_only = render(near, camera, options);
  const Image far_only = render(far, camera, options);
  const float* centre_near = near_only.pixel(32, 32);
  const float* centre_far = far_only.pixel(32, 32);
  ASSERT_GT(std::abs(luminance(centre_near) - luminance(centre_far)), 0.05);
  for (const RenderMesh& scene : {both(near, far), both(far, near)}) {  // either drawing order
    const Image image = render(scene, camera, options);
    for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(image.pixel(32, 32)[k], centre_near[k]);
  }
}

TEST(Raster, BrightestPixelFacesTheLight) {
  const RenderMesh sphere = icosphere(5);
  RenderOptions options;
  options.width = options.height = 256;
  options.supersample = false;
  options.specular = 0.0;  // highlight would sit on the half vector, not the light direction
  options.ambient = 0.0;   // sky-ground ambient would tilt the maximum towards "up"
  const Camera camera = frame_camera(sphere.positions, ViewAngles{}, options.width, options.height);
  const Image image = render(sphere, camera, options);

  int best_x = 0, best_y = 0;
  double best = -1.0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (!is_background(image.pixel(x, y), options) && luminance(image.pixel(x, y)) > best) {
        best = luminance(image.pixel(x, y));
        best_x = x;
        best_y = y;
      }

  // Ray through the centre of that pixel, hit on the unit sphere: the sphere's normal there.
  const Basis b = basis(camera);
  const double tan_v = std::tan(0.5 * camera.fov_y_deg * kPi / 180.0);
  const double nx = (best_x + 0.5) / options.width * 2.0 - 1.0;
  const double ny = 1.0 - (best_y + 0.5) / options.height * 2.0;
  const glm::dvec3 ray = glm::normalize(b.forward + b.right * (nx * tan_v * camera.aspect) + b.up * (ny * tan_v));
  const double along = -glm::dot(camera.eye, ray);
  const double miss2 = glm::dot(camera.eye, camera.eye) - along * along;
  ASSERT_LT(miss2, 1.0) << "brightest pixel is not on the sphere";
  const glm::dvec3 normal = glm::normalize(camera.eye + ray * (along - std::sqrt(1.0 - miss2)));

  const glm::dvec3 l = options.light_in_view;
  const glm::dvec3 light = glm::normalize(b.right * l.x + b.up * l.y - b.forward * l.z);
  const double angle_deg = std::acos(std::clamp(glm::dot(normal, light), -1.0, 1.0)) * 180.0 / kPi;
  EXPECT_LT(angle_deg, 3.0);
}

TEST(Raster, TwoSidedLightingIgnoresWindingAndNormalOrientation) {
  const RenderMesh sphere = icosphere(3);
  RenderMesh scrambled = sphere;
  // Every other triangle wound the other way round.
  for (std::size_t t = 0; t < scrambled.triangles.size(); t += 2)
    std::swap(scrambled.triangles[t].y, scrambled.triangles[t].z);
  // Inward normals everywhere (flipping only some would change the interpolation itself).
  for (glm::dvec3& n : scrambled.normals) n = -n;

  RenderOptions options;
  options.width = options.height = 128;
  const Camera camera = frame_camera(sphere.positions, ViewAngles{}, options.width, options.height);
  const Image reference = render(sphere, camera, options);
  const Image image = render(scrambled, camera, options);
  EXPECT_LT(max_difference(reference, image), 1e-4);
}

TEST(Raster, WireframeAddsEdgePixelsOnlyOnTheSurface) {
  const RenderMesh sphere = icosphere(2);
  RenderOptions options;
  options.width = options.height = 200;
  const Camera camera = frame_camera(sphere.positions, ViewAngles{}, options.width, options.height);
  const Image plain = render(sphere, camera, options);
  options.wireframe = true;
  const Image wired = render(sphere, camera, options);

  std::size_t darker = 0;
  for (int y = 0; y < plain.height; ++y)
    for (int x = 0; x < plain.width; ++x) {
      const float* p = plain.pixel(x, y);
      const float* w = wired.pixel(x, y);
      if (is_background(p, options)) {
        for (int k = 0; k < 3; ++k) ASSERT_FLOAT_EQ(w[k], p[k]) << "wire outside the surface at " << x << "," << y;
      } else if (luminance(w) < luminance(p) - 0.05) {
        ++darker;
      }
    }
  // 320 triangles, about half visible, edges tens of pixels long: thousands of edge pixels,
  // yet far from all of the ~29000 covered pixels.
  const std::size_t covered = count_covered(plain, options);
  EXPECT_GT(darker, covered / 20);
  EXPECT_LT(darker, covered / 2);

  // Secondary edges (flags clear) are lighter than primary ones.
  RenderMesh secondary = sphere;
  secondary.edge_flags.assign(sphere.triangles.size(), 0);
  const Image light_wires = render(secondary, camera, options);
  double sum_primary = 0.0, sum_secondary = 0.0;
  for (int y = 0; y < plain.height; ++y)
    for (int x = 0; x < plain.width; ++x) {
      sum_primary += luminance(wired.pixel(x, y));
      sum_secondary += luminance(light_wires.pixel(x, y));
    }
  EXPECT_GT(sum_secondary, sum_primary);
}

TEST(Raster, WireframeOfHiddenTrianglesStaysHidden) {
  Camera camera;
  camera.eye = {0, 0, 5};
  camera.up = {0, 1, 0};
  RenderOptions options;
  options.width = options.height = 64;
  RenderMesh scene;  // a small far triangle entirely behind a large near one
  scene.positions = {{-3, -3, 1}, {3, -3, 1}, {0, 3, 1}, {-0.3, -0.3, 0}, {0.3, -0.3, 0}, {0, 0.3, 0}};
  scene.normals.assign(6, {0, 0, 1});
  scene.triangles = {{0, 1, 2}, {3, 4, 5}};
  RenderMesh front_only = scene;
  front_only.triangles.pop_back();
  options.wireframe = true;
  const Image a = render(scene, camera, options);
  const Image b = render(front_only, camera, options);
  EXPECT_EQ(max_difference(a, b), 0.0);
}

TEST(Raster, SideBySideKeepsPanelsAndSeparator) {
  const Image left = constant_image(5, 3, 0.25f), right = constant_image(7, 3, 0.75f);
  const Image both = side_by_side(left, right, glm::dvec3(0.5));
  ASSERT_EQ(both.width, 5 + kSeparatorWidth + 7);
  ASSERT_EQ(both.height, 3);
  EXPECT_FLOAT_EQ(both.pixel(4, 2)[0], 0.25f);
  EXPECT_FLOAT_EQ(both.pixel(5, 1)[1], 0.5f);
  EXPECT_FLOAT_EQ(both.pixel(5 + kSeparatorWidth - 1, 0)[2], 0.5f);
  EXPECT_FLOAT_EQ(both.pixel(5 + kSeparatorWidth, 0)[0], 0.75f);
  EXPECT_THROW(side_by_side(left, constant_image(7, 4, 0.f), glm::dvec3(0.5)), std::invalid_argument);
}

TEST(Raster, BandsMatchAWholeRender) {
  const RenderMesh sphere = icosphere(3);
  RenderOptions options;
  options.width = 90;
  options.height = 150;  // more than one internal band
  options.wireframe = true;
  const Camera camera = frame_camera(sphere.positions, ViewAngles{20.0, -30.0}, options.width, options.height);
  const Renderer renderer(sphere, camera, options);
  const Image whole = renderer.render();
  const Image top = renderer.render_rows(0, 77), bottom = renderer.render_rows(77, 150);
  std::vector<float> joined = top.rgb;
  joined.insert(joined.end(), bottom.rgb.begin(), bottom.rgb.end());
  EXPECT_EQ(joined, whole.rgb);
}

TEST(Raster, ImageSizeLimits) {
  RenderOptions options;
  options.width = 0;
  EXPECT_THROW(validate(options), InputError);
  options.width = 10;
  options.height = kMaxImageSide + 1;
  EXPECT_THROW(validate(options), InputError);
}

TEST(Raster, FramingRejectsBadAngles) {
  const RenderMesh sphere = icosphere(0);
  EXPECT_THROW(frame_camera(sphere.positions, ViewAngles{0.0, 91.0}, 10, 10), InputError);
  EXPECT_THROW(frame_camera(sphere.positions, ViewAngles{NAN, 0.0}, 10, 10), InputError);
  EXPECT_THROW(frame_camera({}, ViewAngles{}, 10, 10), InputError);
  // Straight down is allowed and still frames the sphere.
  const Camera top = frame_camera(sphere.positions, ViewAngles{0.0, 90.0}, 10, 10);
  EXPECT_GT(top.eye.y, 1.0);
}

TEST(Raster, BadExtensionOrDirectoryLeavesNoFile) {
  TempDir dir;
  const Image image = constant_image(8, 8, 0.5f);
  EXPECT_THROW(write_image(image, dir.path() / "out.bmp"), InputError);
  EXPECT_THROW(write_image(image, dir.path() / "out"), InputError);
  EXPECT_THROW(write_image(image, dir.path() / "missing" / "out.png"), InputError);
  EXPECT_TRUE(dir.entries().empty());
}

TEST(Raster, UnfinishedImageLeavesNoFile) {
  TempDir dir;
  {
    ImageFileWriter writer(dir.path() / "partial.png", 8, 8);
    writer.write_rows(constant_image(8, 4, 0.5f));
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(Raster, PngAndExrReadBackAtTheirResolution) {
  TempDir dir;
  Image image = constant_image(37, 23, 0.5f);
  image.pixel(36, 22)[0] = 1.0f;  // a marker in the last pixel (bottom right)
  for (const char* name : {"out.png", "OUT.EXR"}) {
    const fs::path path = dir.path() / name;
    write_image(image, path);
    auto in = OIIO::ImageInput::open(path.string());
    ASSERT_TRUE(in) << OIIO::geterror();
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.width, 37);
    EXPECT_EQ(spec.height, 23);
    EXPECT_EQ(spec.nchannels, 3);
    std::vector<float> pixels(37 * 23 * 3);
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, pixels.data()));
    in->close();
    const bool png = path.extension() == ".png";
    // PNG stores sRGB: linear 0.5 encodes to 188/255; EXR stores linear half floats.
    const float mid = png ? 188.0f / 255.0f : 0.5f;
    EXPECT_NEAR(pixels[0], mid, 1e-3) << name;
    EXPECT_NEAR(pixels[(22 * 37 + 36) * 3 + 0], 1.0f, 1e-3) << name;
    EXPECT_NEAR(pixels[(22 * 37 + 36) * 3 + 1], mid, 1e-3) << name;
  }
  auto entries = dir.entries();
  std::sort(entries.begin(), entries.end());
  EXPECT_EQ(entries, (std::vector<fs::path>{"OUT.EXR", "out.png"}));  // no temporaries left
}

// A small square in front of a large one, seen head-on: the contour map holds the large square's
// outline against the background and the small one's against the large one (an interior occluding
// contour), each as the inner ring of samples of its rectangle, on every row including the rows
// next to a band edge; the image border is not a contour; coverage is the large square's rows.
TEST(Raster, ContoursAreTheOutlineAndTheOccludingEdges) {
  auto square = [](double half, double z, RenderMesh& m) {
    const auto base = static_cast<unsigned>(m.positions.size());
    for (const glm::dvec2 c : {glm::dvec2(-half, -half), glm::dvec2(half, -half), glm::dvec2(half, half),
                               glm::dvec2(-half, half)}) {
      m.positions.push_back({c.x, c.y, z});
      m.normals.push_back({0, 0, 1});
    }
    m.triangles.push_back(glm::uvec3(0, 1, 2) + glm::uvec3(base));
    m.triangles.push_back(glm::uvec3(0, 2, 3) + glm::uvec3(base));
  };
  RenderMesh scene;
  square(1.0, 0.0, scene);
  square(0.3, 1.0, scene);
  RenderOptions options;
  options.width = 150;
  options.height = 200;  // several bands of rows
  options.supersample = false;
  // Shifting the camera moves the squares' edges across the bands' edges.
  for (double shift : {0.0, 0.013, 0.031, 0.047}) {
    Camera camera;
    camera.eye = {0, shift, 7};
    camera.target = {0, shift, 0};
    camera.aspect = 0.75;
    const ContourMap map = Renderer(scene, camera, options).contours(0.5);
    ASSERT_EQ(map.width, 150);
    ASSERT_EQ(map.height, 200);
    std::vector<std::vector<bool>> contour(200, std::vector<bool>(150, false));
    for (std::size_t i = 0; i < map.contour.size(); i += 2) contour[map.contour[i + 1]][map.contour[i]] = true;
    // Each square's covered rectangle, from the coverage of each row (rows with two runs never occur:
    // the small square lies inside the large one).
    int top = -1, bottom = -1, left = 0, right = 0;
    for (std::size_t i = 0; i < map.coverage.size(); i += 3) {
      const int y = static_cast<int>(map.coverage[i]);
      if (top < 0) top = y;
      ASSERT_LT(bottom, y) << "x " << map.coverage[i + 1] << ".." << map.coverage[i + 2] << " after " << left
                           << ".." << right << " shift " << shift;
      bottom = y;
      left = static_cast<int>(map.coverage[i + 1]);
      right = static_cast<int>(map.coverage[i + 2]) - 1;
    }
    ASSERT_GT(bottom - top, 100) << shift;
    std::size_t on_outline = 0;
    int inner_left = right, inner_right = left, inner_top = bottom, inner_bottom = top;
    std::vector<glm::ivec2> inner;
    for (int y = top; y <= bottom; ++y)
      for (int x = left; x <= right; ++x) {
        if (!contour[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)]) continue;
        if (y == top || y == bottom || x == left || x == right) {
          ++on_outline;
          continue;
        }
        inner.emplace_back(x, y);
        inner_left = std::min(inner_left, x);
        inner_right = std::max(inner_right, x);
        inner_top = std::min(inner_top, y);
        inner_bottom = std::max(inner_bottom, y);
      }
    const std::size_t ring_samples = static_cast<std::size_t>(2 * (right - left + 1) + 2 * (bottom - top + 1) - 4);
    EXPECT_EQ(on_outline, ring_samples) << shift;
    // Inside: exactly the small square's inner ring (it is nearer than the large one by 1 > 0.5),
    // 0.3 / 1.0 of the large one's size seen from 7 / 6 nearer: 0.35 of its width.
    const int w = inner_right - inner_left + 1, h = inner_bottom - inner_top + 1;
    EXPECT_NEAR(w, 0.35 * (right - left + 1), 2.0) << shift;
    EXPECT_NEAR(h, 0.35 * (bottom - top + 1), 2.0) << shift;
    EXPECT_EQ(inner.size(), static_cast<std::size_t>(2 * w + 2 * h - 4)) << shift;
    for (const glm::ivec2& p : inner)
      EXPECT_TRUE(p.x == inner_left || p.x == inner_right || p.y == inner_top || p.y == inner_bottom)
          << p.x << "," << p.y << " shift " << shift;
    // A jump larger than the squares' distance: the small square's outline is no contour.
    const ContourMap flat = Renderer(scene, camera, options).contours(1.5);
    EXPECT_EQ(flat.contour.size() / 2, ring_samples) << shift;
    EXPECT_EQ(flat.coverage, map.coverage);
  }
  // A square larger than the view: covered everywhere, no contour at the border.
  RenderMesh wall;
  square(100.0, 0.0, wall);
  Camera camera;
  camera.eye = {0, 0, 5};
  camera.aspect = 0.75;
  const ContourMap map = Renderer(wall, camera, options).contours(0.5);
  EXPECT_TRUE(map.contour.empty());
  EXPECT_EQ(map.coverage.size(), 3u * 200);
  EXPECT_THROW((void)Renderer(wall, camera, options).contours(0.0), std::invalid_argument);
}
