#include "render/annotate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace tessim::render {

namespace {

#include "render/render_tables.inc"

constexpr int kPad = 4;  // pixels around text and bars

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

int hex_value(char c) { return c <= '9' ? c - '0' : c - 'a' + 10; }

void fill(Image& image, int x0, int y0, int x1, int y1, const glm::dvec3& colour) {
  for (int y = std::max(0, y0); y < std::min(image.height, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(image.width, x1); ++x) {
      float* p = image.pixel(x, y);
      for (int c = 0; c < 3; ++c) p[c] = static_cast<float>(colour[c]);
    }
}

}  // namespace

int text_width(std::string_view text, int scale) { return static_cast<int>(text.size()) * kGlyphWidth * scale; }
int text_line_height(int scale) { return kGlyphHeight * scale; }

void draw_text(Image& image, int x, int y_top, std::string_view text, const glm::dvec3& colour, int scale) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto code = static_cast<unsigned char>(text[i]);
    const char* glyph = kGlyphs[(code >= 32 && code <= 126 ? code : '?') - 32];
    const int gx = x + static_cast<int>(i) * kGlyphWidth * scale;
    for (int row = 0; row < kGlyphHeight * scale; ++row) {
      const int py = y_top + row;
      if (py < 0 || py >= image.height) continue;
      for (int col = 0; col < kGlyphWidth * scale; ++col) {
        const int px = gx + col;
        if (px < 0 || px >= image.width) continue;
        // Coverage is blended in sRGB-like space would look bolder; linear keeps edges thin.
        const double a = hex_value(glyph[(row / scale) * kGlyphWidth + col / scale]) / 15.0;
        if (a == 0.0) continue;
        float* p = image.pixel(px, py);
        for (int c = 0; c < 3; ++c) p[c] = static_cast<float>((1.0 - a) * p[c] + a * colour[c]);
      }
    }
  }
}

std::string fit_text(std::string_view text, int width, int scale) {
  if (text_width(text, scale) <= width) return std::string(text);
  const int chars = width / (kGlyphWidth * scale);
  if (chars <= 3) return std::string(text.substr(0, static_cast<std::size_t>(std::max(0, chars))));
  return std::string(text.substr(0, static_cast<std::size_t>(chars - 3))) + "...";
}

glm::dvec3 colormap(double t) {
  constexpr int last = static_cast<int>(std::size(kViridis)) - 1;
  const double x = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0) * last;
  const int i = std::min(last - 1, static_cast<int>(x));
  const double f = x - i;
  glm::dvec3 out;
  for (int c = 0; c < 3; ++c)
    out[c] = srgb_to_linear((1.0 - f) * kViridis[i][c] + f * kViridis[i + 1][c]);
  return out;
}

std::vector<double> nice_ticks(double lo, double hi, int max_ticks) {
  std::vector<double> ticks;
  if (!(hi > lo) || max_ticks < 2) return {lo};
  const double raw = (hi - lo) / (max_ticks - 1);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = magnitude;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * magnitude >= raw) {
      step = m * magnitude;
      break;
    }
  for (double v = std::ceil(lo / step) * step; v <= hi + step * 1e-9; v += step)
    ticks.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
  return ticks;
}

std::string format_tick(double value) {
  char buf[32];
  const double a = std::abs(value);
  if (a != 0.0 && (a < 1e-3 || a >= 1e4)) std::snprintf(buf, sizeof buf, "%.2g", value);
  else std::snprintf(buf, sizeof buf, "%.3g", value);
  return buf;
}

Image colour_bar_strip(const ColourScale& scale, int width, const glm::dvec3& background, int text_scale,
                       glm::dvec3 (*map)(double)) {
  const int line = text_line_height(text_scale);
  const int bar_height = 12 * text_scale;
  const int tick_length = 4 * text_scale;
  const glm::dvec3 ink(0.08, 0.08, 0.10);

  const std::string title = scale.title + (scale.clipped_above ? " (larger values shown as the top colour)" : "");
  const std::vector<std::string> title_lines = wrap_text(title, width - 2 * kPad, text_scale);
  const int title_height = static_cast<int>(title_lines.size()) * line;
  const int height = kPad + title_height + kPad + bar_height + tick_length + line + kPad;
  Image strip(width, height);
  fill(strip, 0, 0, width, height, background);
  for (std::size_t i = 0; i < title_lines.size(); ++i)
    draw_text(strip, kPad, kPad + static_cast<int>(i) * line, title_lines[i], ink, text_scale);

  // The bar spans the strip but leaves room for half a label at either end.
  const int margin = kPad + text_width("0.000", text_scale) / 2;
  const int x0 = margin, x1 = std::max(margin + 2, width - margin);
  const int bar_top = kPad + title_height + kPad;
  for (int x = x0; x < x1; ++x)
    fill(strip, x, bar_top, x + 1, bar_top + bar_height, map((x - x0 + 0.5) / (x1 - x0)));
  fill(strip, x0 - 1, bar_top - 1, x1 + 1, bar_top, ink);
  fill(strip, x0 - 1, bar_top + bar_height, x1 + 1, bar_top + bar_height + 1, ink);
  fill(strip, x0 - 1, bar_top, x0, bar_top + bar_height, ink);
  fill(strip, x1, bar_top, x1 + 1, bar_top + bar_height, ink);

  const int max_ticks = std::clamp((x1 - x0) / text_width("0.0000 ", text_scale), 2, 6);
  for (double v : nice_ticks(scale.lo, scale.hi, max_ticks)) {
    const int x = x0 + static_cast<int>(std::lround(scale.position(v) * (x1 - x0 - 1)));
    fill(strip, x, bar_top + bar_height, x + text_scale, bar_top + bar_height + tick_length, ink);
    const std::string label = format_tick(v);
    const int lx = std::clamp(x - text_width(label, text_scale) / 2, 0, width - text_width(label, text_scale));
    draw_text(strip, lx, bar_top + bar_height + tick_length, label, ink, text_scale);
  }
  return strip;
}

std::vector<std::string> wrap_text(std::string_view text, int width, int scale) {
  const auto per_line = static_cast<std::size_t>(std::max(1, width / (kGlyphWidth * scale)));
  std::vector<std::string> lines;
  std::string_view rest = text;
  while (rest.size() > per_line) {
    // The last space that keeps the line within the width, else a cut inside the word.
    const std::size_t space = rest.substr(0, per_line + 1).rfind(' ');
    const std::size_t cut = space == std::string_view::npos || space == 0 ? per_line : space;
    lines.emplace_back(rest.substr(0, cut));
    rest.remove_prefix(cut);
    while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
  }
  if (!rest.empty() || lines.empty()) lines.emplace_back(rest);
  return lines;
}

Image stack(const Image& top, const Image& bottom) {
  if (top.width != bottom.width) throw std::logic_error("stack: images of different widths");
  Image out(top.width, top.height + bottom.height);
  std::copy(top.rgb.begin(), top.rgb.end(), out.rgb.begin());
  std::copy(bottom.rgb.begin(), bottom.rgb.end(), out.rgb.begin() + static_cast<std::ptrdiff_t>(top.rgb.size()));
  return out;
}

Image caption_strip(const std::vector<CaptionLine>& lines, int width, const glm::dvec3& background, int text_scale) {
  const int line = text_line_height(text_scale);
  // Every cell wrapped to its width; a caption line is as tall as its tallest cell.
  std::vector<std::vector<std::vector<std::string>>> wrapped(lines.size());
  int height = kPad;
  for (std::size_t l = 0; l < lines.size(); ++l) {
    std::size_t rows = 1;
    for (std::size_t c = 0; c < lines[l].cells.size(); ++c) {
      wrapped[l].push_back(wrap_text(lines[l].cells[c], lines[l].width[c] - 2 * kPad, text_scale));
      rows = std::max(rows, wrapped[l].back().size());
    }
    height += static_cast<int>(rows) * line + kPad;
  }
  Image strip(width, height);
  fill(strip, 0, 0, width, height, background);
  const glm::dvec3 ink(0.08, 0.08, 0.10);
  int y = kPad;
  for (std::size_t l = 0; l < lines.size(); ++l) {
    std::size_t rows = 1;
    for (std::size_t c = 0; c < wrapped[l].size(); ++c) {
      for (std::size_t r = 0; r < wrapped[l][c].size(); ++r)
        draw_text(strip, lines[l].x[c] + kPad, y + static_cast<int>(r) * line, wrapped[l][c][r], ink, text_scale);
      rows = std::max(rows, wrapped[l][c].size());
    }
    y += static_cast<int>(rows) * line + kPad;
  }
  return strip;
}

}  // namespace tessim::render
