// What pictures say must be readable whole: captions wrap instead of being cut (at any image
// width), and the SVG and the raster come from one drawing. The pictures `tessim render` and
// `tessim pattern` write: tests/cli/picture_cli_test.cpp.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/annotate.hpp"
#include "render/canvas.hpp"

namespace tessim::render {
namespace {

const std::string kLongCaption =
    "Wuson.ply: D3D11 pattern fractional_odd adaptive (camera eye 2.6,1.3,-2.9 target 0,0.6,-0.2 fov 45, "
    "viewport 1024x768, 10 pixels per segment), quadratic normals, wireframe coloured by factor END";

TEST(CaptionWrap, LinesKeepEveryWordWithinTheWidth) {
  const int width = 300;
  const std::vector<std::string> lines = wrap_text(kLongCaption, width);
  ASSERT_GT(lines.size(), 3u);
  std::string joined;
  for (const std::string& l : lines) {
    EXPECT_LE(text_width(l), width) << l;
    EXPECT_FALSE(l.empty());
    joined += (joined.empty() ? "" : " ") + l;
  }
  EXPECT_EQ(joined, kLongCaption);  // broken only at spaces here: nothing lost, nothing cut
  // A word longer than a line is cut inside, still without losing a character.
  const std::vector<std::string> word = wrap_text(std::string(50, 'x'), 80);
  EXPECT_EQ(word.size(), 5u);
  EXPECT_EQ(wrap_text("", 80), std::vector<std::string>{""});
}

TEST(CaptionWrap, StripGrowsWithTheTextInsteadOfCuttingIt) {
  const glm::dvec3 background(1.0);
  const Image one_line = caption_strip({{{"short"}, {0}, {320}}}, 320, background);
  const Image wrapped = caption_strip({{{kLongCaption}, {0}, {320}}}, 320, background);
  const int lines = static_cast<int>(wrap_text(kLongCaption, 320 - 8).size());
  EXPECT_GT(lines, 4);
  EXPECT_EQ(wrapped.height - one_line.height, (lines - 1) * text_line_height());
  // The last line holds the caption's last word: ink in the strip's bottom text row.
  int ink = 0;
  for (int y = wrapped.height - text_line_height() - 4; y < wrapped.height; ++y)
    for (int x = 0; x < wrapped.width; ++x) ink += wrapped.pixel(x, y)[0] < 0.5f;
  EXPECT_GT(ink, 20);
}

TEST(PatternPicture, SvgAndRasterComeFromOneDrawing) {
  Drawing d;
  d.width = 200;
  d.height = 100;
  d.polygons.push_back({{{10, 10}, {190, 10}, {100, 90}}, glm::dvec3(0.8, 0.9, 1.0), glm::dvec3(0.0), 2.0});
  d.dots.push_back({{100, 40}, 6.0, glm::dvec3(1.0, 0.0, 0.0)});
  d.texts.push_back({{20, 98}, "a<b & c", glm::dvec3(0.0)});
  const std::string svg = to_svg(d);
  EXPECT_NE(svg.find("<polygon points=\"10,10 190,10 100,90\" fill=\"#cce6ff\" stroke=\"#000000\""),
            std::string::npos)
      << svg;
  EXPECT_NE(svg.find("<circle cx=\"100\" cy=\"40\" r=\"6\" fill=\"#ff0000\"/>"), std::string::npos) << svg;
  EXPECT_NE(svg.find(">a&lt;b &amp; c</text>"), std::string::npos) << svg;
  const Image image = rasterize(d, 400, 200);  // twice the size
  const float* dot = image.pixel(200, 80);
  EXPECT_GT(dot[0], 0.9f);
  EXPECT_LT(dot[1], 0.1f);
  const float* fill = image.pixel(200, 50);  // inside the triangle, away from the dot
  EXPECT_GT(fill[2], 0.9f);
  EXPECT_LT(fill[0], 0.7f);
  const float* outside = image.pixel(5, 190);
  EXPECT_GT(outside[0], 0.99f);
}

}  // namespace
}  // namespace tessim::render
