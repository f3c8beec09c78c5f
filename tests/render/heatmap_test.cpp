// Pictures that measure: text and colour bars (render/annotate.hpp), heat maps of per-vertex
// values, the choice of the model's best side. `tessim render --color` end to end:
// tests/cli/render_cli_test.cpp.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "model/base/error.hpp"
#include "render/annotate.hpp"
#include "render/raster.hpp"

using namespace tessim::render;

namespace {

double luminance(const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

std::size_t inked(const Image& image, const glm::dvec3& background) {
  std::size_t n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      n += std::abs(image.pixel(x, y)[0] - background.r) > 0.05f;
  return n;
}

// A unit cube centred at the origin, each face split into n x n quads (two triangles each)
// except the face towards +X, split into 4n x 4n: the side with the detail.
RenderMesh box_with_detailed_side(int n) {
  RenderMesh m;
  auto face = [&](const glm::dvec3& centre, const glm::dvec3& a, const glm::dvec3& b, int cells) {
    const auto base = static_cast<unsigned>(m.positions.size());
    const glm::dvec3 normal = glm::normalize(glm::cross(a, b));
    for (int j = 0; j <= cells; ++j)
      for (int i = 0; i <= cells; ++i) {
        m.positions.push_back(centre + a * (2.0 * i / cells - 1.0) + b * (2.0 * j / cells - 1.0));
        m.normals.push_back(normal);
      }
    for (int j = 0; j < cells; ++j)
      for (int i = 0; i < cells; ++i) {
        const unsigned v = base + static_cast<unsigned>(j * (cells + 1) + i);
        m.triangles.emplace_back(v, v + 1, v + cells + 2);
        m.triangles.emplace_back(v, v + cells + 2, v + cells + 1);
      }
  };
  const glm::dvec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
  face(X, Y, Z, 4 * n);  // +X: the detailed side
  face(-X, Z, Y, n);
  face(Y, Z, X, n);
  face(-Y, X, Z, n);
  face(Z, X, Y, n);
  face(-Z, Y, X, n);
  return m;
}

}  // namespace

TEST(Annotate, NiceTicksCoverTheRangeInRoundSteps) {
  EXPECT_EQ(nice_ticks(0.0, 1.0, 6), (std::vector<double>{0.0, 0.2, 0.4, 0.6000000000000001, 0.8, 1.0}));
  const std::vector<double> t = nice_ticks(0.0, 1.15e-6, 6);
  ASSERT_GE(t.size(), 3u);
  EXPECT_EQ(t.front(), 0.0);
  EXPECT_LE(t.back(), 1.15e-6);
  EXPECT_LE(t.size(), 6u);
  for (std::size_t i = 1; i < t.size(); ++i) EXPECT_NEAR(t[i] - t[i - 1], t[1] - t[0], 1e-18);
  EXPECT_EQ(nice_ticks(2.0, 2.0), std::vector<double>{2.0});  // an empty range: one tick
}

TEST(Annotate, TickLabelsAreShortAndExact) {
  EXPECT_EQ(format_tick(0.0), "0");
  EXPECT_EQ(format_tick(0.02), "0.02");
  EXPECT_EQ(format_tick(5e-7), "5e-07");
  EXPECT_EQ(format_tick(3.14159), "3.14");
  EXPECT_EQ(format_tick(25000.0), "2.5e+04");
}

TEST(Annotate, ColourMapRunsDarkToBright) {
  double previous = -1.0;
  for (int i = 0; i <= 20; ++i) {
    const double l = luminance(colormap(i / 20.0));
    EXPECT_GT(l, previous) << i;  // viridis: luminance rises monotonically
    previous = l;
  }
  EXPECT_EQ(colormap(-3.0), colormap(0.0));  // clamped
  EXPECT_EQ(colormap(7.0), colormap(1.0));
  EXPECT_EQ(colormap(std::nan("")), colormap(0.0));
}

TEST(Annotate, TextInksOnlyItsBox) {
  const glm::dvec3 white(1.0), black(0.0);
  Image image(100, 40);
  std::fill(image.rgb.begin(), image.rgb.end(), 1.0f);
  draw_text(image, 10, 5, "Aq1", black);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const bool inside = x >= 10 && x < 10 + text_width("Aq1") && y >= 5 && y < 5 + text_line_height();
      if (!inside) {
        EXPECT_EQ(image.pixel(x, y)[0], 1.0f) << x << "," << y;
      }
    }
  EXPECT_GT(inked(image, white), 30u);
  Image doubled(100, 40);
  std::fill(doubled.rgb.begin(), doubled.rgb.end(), 1.0f);
  draw_text(doubled, 0, 0, "Aq1", black, 2);
  EXPECT_EQ(inked(doubled, white), 4 * inked(image, white));  // scale 2: every pixel four times
  EXPECT_EQ(fit_text("position error", text_width("position")), "posit...");
  EXPECT_EQ(fit_text("short", 1000), "short");
}

TEST(Annotate, ColourBarShowsTheMapFromLowToHigh) {
  ColourScale scale;
  scale.hi = 0.05;
  scale.title = "distance";
  const glm::dvec3 background(0.94);
  const Image bar = colour_bar_strip(scale, 400, background);
  // Somewhere a row holds the whole map: darkest on the left, brightest on the right.
  int best_row = -1;
  for (int y = 0; y < bar.height && best_row < 0; ++y) {
    const float* left = bar.pixel(60, y);
    const float* right = bar.pixel(340, y);
    const glm::dvec3 l(left[0], left[1], left[2]), r(right[0], right[1], right[2]);
    if (glm::length(l - background) > 0.1 && glm::length(r - background) > 0.1 && luminance(r) > luminance(l) + 0.3)
      best_row = y;
  }
  EXPECT_GE(best_row, 0);
  EXPECT_GT(inked(bar, background), 400u);  // title and labels
}

TEST(Raster, ScalarsColourTheSurfaceThroughTheMap) {
  RenderMesh quad;
  quad.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  quad.normals.assign(4, glm::dvec3(0, 0, 1));
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  quad.scalars = {0.0, 1.0, 1.0, 0.0};  // 0 on the left edge, 1 on the right
  RenderOptions options;
  options.width = 80;
  options.height = 80;
  ViewAngles front;
  front.azimuth_deg = 0.0;
  front.elevation_deg = 0.0;
  const Image image = render(quad, frame_camera(quad.positions, front, 80, 80), options);
  const float* left = image.pixel(12, 40);
  const float* right = image.pixel(68, 40);
  // viridis: blue-violet at 0 (blue above green), yellow at 1 (green above blue).
  EXPECT_GT(left[2], left[1]);
  EXPECT_GT(right[1], right[2]);
  EXPECT_GT(luminance({right[0], right[1], right[2]}), 2.0 * luminance({left[0], left[1], left[2]}));

  quad.scalars.pop_back();
  EXPECT_THROW(validate(quad, "quad"), tessim::InputError);
}

TEST(Raster, BestViewFacesTheDetailedSide) {
  const ViewAngles view = best_view(box_with_detailed_side(2), UpAxis::Y);
  // +X is azimuth 90 (front +Z, towards +X); of the candidates 35 + 45 k, 80 looks at it most.
  EXPECT_EQ(view.azimuth_deg, 80.0);
  EXPECT_EQ(view.elevation_deg, ViewAngles{}.elevation_deg);
}
