// What the pictures of `tessim render` and `tessim pattern` say must be readable whole: the
// caption wraps instead of being cut at a narrow width, the pattern's PNG carries the same
// points, labels and caption as its SVG, and the adaptive wireframe shows each patch's factor in
// colour, with a colour bar.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "render/annotate.hpp"
#include "tests/support/read_image.hpp"
#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim::app {
namespace {

namespace fs = std::filesystem;
using tessim::testing::read_back;
using tessim::testing::ReadBack;
using tessim::testing::run_tessim;
using tessim::testing::TempDir;
using tessim::testing::TessimRun;

const fs::path kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";
const std::string kLongCaption =
    "Wuson.ply: D3D11 pattern fractional_odd adaptive (camera eye 2.6,1.3,-2.9 target 0,0.6,-0.2 fov 45, "
    "viewport 1024x768, 10 pixels per segment), quadratic normals, wireframe coloured by factor END";

// Pixels of a row range whose every channel is below `level` (the thin font's anti-aliased ink).
int dark_pixels(const ReadBack& image, int y0, int y1, int x0 = 0, int x1 = -1, float level = 0.55f) {
  if (x1 < 0) x1 = image.width;
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const float* p = image.pixel(x, y);
      n += p[0] < level && p[1] < level && p[2] < level;
    }
  return n;
}

TEST(CaptionWrap, RenderAtANarrowWidthShowsTheWholeCaption) {
  ASSERT_TRUE(fs::exists(kWuson)) << kWuson << " not installed (assimp-testmodels)";
  TempDir d;
  const fs::path png = d.path() / "narrow.png";
  const TessimRun r = run_tessim(
      {"render", kWuson.string(), "-L", "1", "--size", "320x200", "--caption", kLongCaption, "-o", png.string()},
      d.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const ReadBack image = read_back(png);
  ASSERT_EQ(image.width, 320);
  const int lines = static_cast<int>(render::wrap_text(kLongCaption, 320 - 8).size());
  // Caption strip: padding, one text row per wrapped line, padding; then the picture.
  EXPECT_EQ(image.height, 200 + 4 + lines * render::text_line_height() + 4);
  const int last_row = 4 + (lines - 1) * render::text_line_height();
  EXPECT_GT(dark_pixels(image, last_row, last_row + render::text_line_height()), 20) << "the last caption line is drawn";
}

TEST(PatternPicture, PngShowsThePointsLabelsAndCaptionOfTheSvg) {
  TempDir d;
  const fs::path png = d.path() / "p.png", svg = d.path() / "p.svg";
  const std::vector<std::string> pattern = {"pattern", "--outer", "3,3,3", "--inner", "3", "--partitioning", "integer"};
  std::vector<std::string> args = pattern;
  args.insert(args.end(), {"--json", "-o", png.string(), "--size", "800x680"});
  const TessimRun r = run_tessim(args, d.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto points = nlohmann::json::parse(r.out)["points"].size();
  args = pattern;
  args.insert(args.end(), {"-o", svg.string()});
  ASSERT_EQ(run_tessim(args, d.path()).status, 0);

  const ReadBack image = read_back(png);
  ASSERT_EQ(image.width, 800);
  ASSERT_EQ(image.height, 680);
  // Point markers: the SVG's dots (#b5402a), radius 5 units at a scale near 1.
  int red = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float* p = image.pixel(x, y);
      red += p[0] > p[1] + 0.25f && p[0] > p[2] + 0.25f;
    }
  EXPECT_GE(red, static_cast<int>(points) * 40) << points << " points";
  // The caption over the domain: ink in the top 40 rows, where the SVG has its title.
  EXPECT_GT(dark_pixels(image, 0, 40), 300);
  // The corner label "w=1" left of the domain's bottom-left corner (SVG x 15..45, below it).
  EXPECT_GT(dark_pixels(image, image.height - 80, image.height, 0, 55), 6);
}

TEST(AdaptiveWireframe, LinesAreColouredByThePatchFactor) {
  ASSERT_TRUE(fs::exists(kWuson)) << kWuson << " not installed (assimp-testmodels)";
  TempDir d;
  const fs::path png = d.path() / "a.png";
  const TessimRun r = run_tessim({"render", kWuson.string(), "--adaptive", "screen", "--camera",
                                  "eye=2.6,1.3,-2.9,target=0,0.6,-0.2,fov=45", "--viewport", "1024x768",
                                  "--pixels-per-segment", "10", "--partitioning", "fractional_odd", "--wireframe",
                                  "--no-caption", "--size", "512x384", "-o", png.string()},
                                 d.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const ReadBack image = read_back(png);
  ASSERT_EQ(image.width, 512);
  ASSERT_GT(image.height, 384) << "a colour bar of the factors under the picture";
  // In the picture itself (the colour bar is below row 384): lines in both halves of the factor
  // scale, blue-violet for coarse patches and red-orange for fine ones. The surface's soft blue
  // shading (green between red and blue) is neither.
  int coarse = 0, fine = 0;
  for (int y = 0; y < 384; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float* p = image.pixel(x, y);
      coarse += p[1] < std::min(p[0], p[2]) - 0.2f && p[2] >= p[0];
      fine += p[0] > p[2] + 0.3f;
    }
  EXPECT_GT(coarse, 500);
  EXPECT_GT(fine, 500);
  // The bar spans the scale: its left end coarse, its right end fine.
  int bar_coarse = 0, bar_fine = 0;
  for (int y = 384; y < image.height; ++y) {
    const float* left = image.pixel(40, y);
    const float* right = image.pixel(image.width - 40, y);
    bar_coarse += left[2] > left[0] + 0.3f;
    bar_fine += right[0] > right[2] + 0.3f;
  }
  EXPECT_GT(bar_coarse, 5);
  EXPECT_GT(bar_fine, 5);
}

}  // namespace
}  // namespace tessim::app
