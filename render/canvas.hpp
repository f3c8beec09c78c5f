// A flat vector picture (polygons, dots, text) kept as a list of shapes and drawn by two
// back ends from the same list: as SVG text and rasterized into an Image with the built-in
// bitmap font (render/annotate.hpp). A picture offered as SVG and as PNG thereby shows the same
// things in both (tessim pattern).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "render/raster.hpp"

namespace tessim::render {

// Colours as in SVG: sRGB components in [0, 1].
struct Drawing {
  struct Polygon {
    std::vector<glm::dvec2> points;  // convex
    std::optional<glm::dvec3> fill;
    std::optional<glm::dvec3> stroke;
    double stroke_width = 1.0;
  };
  struct Dot {
    glm::dvec2 centre;
    double radius = 1.0;
    glm::dvec3 fill;
  };
  struct Text {
    glm::dvec2 baseline_left;  // SVG's (x, y) of a text element
    std::string text;
    glm::dvec3 colour{0.0};
  };
  double width = 100.0, height = 100.0;  // user units (SVG pixels), y down
  glm::dvec3 background{1.0};
  double font_size = 15.0;  // of every text, user units
  // Drawn in this order: every polygon (fill, then its outline), every dot, every text.
  std::vector<Polygon> polygons;
  std::vector<Dot> dots;
  std::vector<Text> texts;
};

// "#rrggbb".
std::string svg_colour(const glm::dvec3& srgb);

// The drawing as an SVG document of width x height user units.
std::string to_svg(const Drawing& drawing);

// The drawing scaled uniformly to fit `width` x `height` pixels, centred on the background, 4x4
// samples per pixel for polygons and dots; text in the bitmap font at the integer scale nearest
// the drawing's font size.
Image rasterize(const Drawing& drawing, int width, int height);

}  // namespace tessim::render
