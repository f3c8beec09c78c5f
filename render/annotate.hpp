// What a picture needs besides the surface: text (captions, labels), a colour map for heat maps
// and the colour bar that gives its scale. Text is drawn from a built-in bitmap font
// (render_tables.inc), so pictures need no font at run time and are the same on every machine.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "render/raster.hpp"

namespace tessim::render {

// Pixel size of one line of text at an integer scale (1: 8x16-pixel characters).
int text_width(std::string_view text, int scale = 1);
int text_line_height(int scale = 1);

// Draws `text` with its top-left corner at (x, y_top), clipped to the image. Characters outside
// printable ASCII are drawn as '?'.
void draw_text(Image& image, int x, int y_top, std::string_view text, const glm::dvec3& colour, int scale = 1);

// `text` shortened with "..." so that it fits in `width` pixels.
std::string fit_text(std::string_view text, int width, int scale = 1);

// viridis at t in [0, 1] (clamped), linear RGB.
glm::dvec3 colormap(double t);

// A linear colour scale from `lo` to `hi` (hi > lo) for heat maps.
struct ColourScale {
  double lo = 0.0, hi = 1.0;
  std::string title;           // what is measured, with its unit
  bool clipped_above = false;  // some values exceed hi and show as hi's colour

  double position(double value) const { return (value - lo) / (hi - lo); }
};

// A strip of `width` pixels: the colour bar from lo to hi in the colours of `map` (t in [0, 1]),
// with ticks and labels under it and the title above it, on `background`.
Image colour_bar_strip(const ColourScale& scale, int width, const glm::dvec3& background, int text_scale = 1,
                       glm::dvec3 (*map)(double) = colormap);

// `top` above `bottom` (both of the same width).
Image stack(const Image& top, const Image& bottom);

// `text` broken into lines of at most `width` pixels: at spaces where it can, inside a word longer
// than a line where it must. At least one line (empty for empty text), at least one character each.
std::vector<std::string> wrap_text(std::string_view text, int width, int scale = 1);

// A strip of text lines; each line has cells, cell i drawn from x[i] in at most width[i] pixels
// (wrapped onto as many text rows as it needs: the strip grows, nothing is cut off), e.g. one
// label per panel of a comparison.
struct CaptionLine {
  std::vector<std::string> cells;
  std::vector<int> x, width;
};
Image caption_strip(const std::vector<CaptionLine>& lines, int width, const glm::dvec3& background,
                    int text_scale = 1);

// Tick values for a scale from lo to hi: 0 and "nice" steps (1, 2, 5 x 10^k), at most max_ticks.
std::vector<double> nice_ticks(double lo, double hi, int max_ticks = 6);

// A tick label: three significant digits, exponent form for very small or large magnitudes.
std::string format_tick(double value);

}  // namespace tessim::render
