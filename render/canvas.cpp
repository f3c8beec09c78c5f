#include "render/canvas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "render/annotate.hpp"

namespace tessim::render {

namespace {

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

glm::dvec3 linear(const glm::dvec3& srgb) {
  return {srgb_to_linear(srgb.r), srgb_to_linear(srgb.g), srgb_to_linear(srgb.b)};
}

std::string xml_escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else out += c;
  }
  return out;
}

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", x);
  std::string s = buf;
  while (s.back() == '0') s.pop_back();  // "12.50" -> "12.5", "3.00" -> "3"
  if (s.back() == '.') s.pop_back();
  return s;
}

// Drawing units to pixels: scaled uniformly, centred.
struct Transform {
  double scale, ox, oy;
  glm::dvec2 operator()(const glm::dvec2& p) const { return {ox + scale * p.x, oy + scale * p.y}; }
};

void blend(Image& image, int x, int y, const glm::dvec3& colour, double alpha) {
  if (alpha <= 0.0 || x < 0 || y < 0 || x >= image.width || y >= image.height) return;
  float* p = image.pixel(x, y);
  for (int c = 0; c < 3; ++c) p[c] = static_cast<float>((1.0 - alpha) * p[c] + alpha * colour[c]);
}

double cross(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& p) {
  return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

void fill_convex(Image& image, const std::vector<glm::dvec2>& pts, const glm::dvec3& colour) {
  if (pts.size() < 3) return;
  double area = 0.0;
  glm::dvec2 lo = pts[0], hi = pts[0];
  for (std::size_t i = 0; i < pts.size(); ++i) {
    area += cross(pts[0], pts[i], pts[(i + 1) % pts.size()]);
    lo = glm::min(lo, pts[i]);
    hi = glm::max(hi, pts[i]);
  }
  if (area == 0.0) return;
  const double orientation = area > 0.0 ? 1.0 : -1.0;
  constexpr int kSide = 4;  // samples per pixel side
  for (int y = std::max(0, static_cast<int>(std::floor(lo.y))); y <= std::min(image.height - 1, static_cast<int>(hi.y)); ++y)
    for (int x = std::max(0, static_cast<int>(std::floor(lo.x))); x <= std::min(image.width - 1, static_cast<int>(hi.x)); ++x) {
      int inside = 0;
      for (int sy = 0; sy < kSide; ++sy)
        for (int sx = 0; sx < kSide; ++sx) {
          const glm::dvec2 p(x + (sx + 0.5) / kSide, y + (sy + 0.5) / kSide);
          bool in = true;
          for (std::size_t i = 0; in && i < pts.size(); ++i)
            in = orientation * cross(pts[i], pts[(i + 1) % pts.size()], p) >= 0.0;
          inside += in;
        }
      blend(image, x, y, colour, static_cast<double>(inside) / (kSide * kSide));
    }
}

// A line of `width` pixels with round ends, its coverage from the distance to the segment.
void stroke_segment(Image& image, const glm::dvec2& a, const glm::dvec2& b, double width, const glm::dvec3& colour) {
  const double half = 0.5 * width;
  const glm::dvec2 lo = glm::min(a, b) - (half + 1.0), hi = glm::max(a, b) + (half + 1.0);
  const glm::dvec2 d = b - a;
  const double length2 = glm::dot(d, d);
  for (int y = std::max(0, static_cast<int>(lo.y)); y <= std::min(image.height - 1, static_cast<int>(hi.y)); ++y)
    for (int x = std::max(0, static_cast<int>(lo.x)); x <= std::min(image.width - 1, static_cast<int>(hi.x)); ++x) {
      const glm::dvec2 p(x + 0.5, y + 0.5);
      const double t = length2 > 0.0 ? std::clamp(glm::dot(p - a, d) / length2, 0.0, 1.0) : 0.0;
      const double distance = glm::length(p - (a + t * d));
      // A line thinner than a pixel covers it in proportion to its width.
      blend(image, x, y, colour, std::clamp(half + 0.5 - distance, 0.0, std::min(1.0, width)));
    }
}

void fill_disc(Image& image, const glm::dvec2& c, double r, const glm::dvec3& colour) {
  for (int y = std::max(0, static_cast<int>(c.y - r - 1)); y <= std::min(image.height - 1, static_cast<int>(c.y + r + 1)); ++y)
    for (int x = std::max(0, static_cast<int>(c.x - r - 1)); x <= std::min(image.width - 1, static_cast<int>(c.x + r + 1)); ++x)
      blend(image, x, y, colour, std::clamp(r + 0.5 - glm::length(glm::dvec2(x + 0.5, y + 0.5) - c), 0.0, 1.0));
}

}  // namespace

std::string svg_colour(const glm::dvec3& srgb) {
  char buf[8];
  const auto byte = [](double c) { return static_cast<int>(std::lround(std::clamp(c, 0.0, 1.0) * 255.0)); };
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", byte(srgb.r), byte(srgb.g), byte(srgb.b));
  return buf;
}

std::string to_svg(const Drawing& d) {
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << number(d.width) << "\" height=\"" << number(d.height)
    << "\" viewBox=\"0 0 " << number(d.width) << " " << number(d.height)
    << "\" font-family=\"sans-serif\" font-size=\"" << number(d.font_size) << "\">\n";
  s << "<rect width=\"100%\" height=\"100%\" fill=\"" << svg_colour(d.background) << "\"/>\n";
  for (const Drawing::Polygon& p : d.polygons) {
    s << "<polygon points=\"";
    for (std::size_t i = 0; i < p.points.size(); ++i)
      s << (i ? " " : "") << number(p.points[i].x) << "," << number(p.points[i].y);
    s << "\" fill=\"" << (p.fill ? svg_colour(*p.fill) : "none") << "\"";
    if (p.stroke)
      s << " stroke=\"" << svg_colour(*p.stroke) << "\" stroke-width=\"" << number(p.stroke_width)
        << "\" stroke-linejoin=\"round\"";
    s << "/>\n";
  }
  for (const Drawing::Dot& c : d.dots)
    s << "<circle cx=\"" << number(c.centre.x) << "\" cy=\"" << number(c.centre.y) << "\" r=\"" << number(c.radius)
      << "\" fill=\"" << svg_colour(c.fill) << "\"/>\n";
  for (const Drawing::Text& t : d.texts)
    s << "<text x=\"" << number(t.baseline_left.x) << "\" y=\"" << number(t.baseline_left.y) << "\" fill=\""
      << svg_colour(t.colour) << "\">" << xml_escaped(t.text) << "</text>\n";
  s << "</svg>\n";
  return s.str();
}

Image rasterize(const Drawing& d, int width, int height) {
  Image image(width, height);
  const glm::dvec3 background = linear(d.background);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float* p = image.pixel(x, y);
      for (int c = 0; c < 3; ++c) p[c] = static_cast<float>(background[c]);
    }
  const double scale = std::min(width / d.width, height / d.height);
  const Transform to_pixels{scale, 0.5 * (width - scale * d.width), 0.5 * (height - scale * d.height)};
  std::vector<glm::dvec2> pts;
  for (const Drawing::Polygon& p : d.polygons) {
    pts.clear();
    for (const glm::dvec2& q : p.points) pts.push_back(to_pixels(q));
    if (p.fill) fill_convex(image, pts, linear(*p.fill));
    if (p.stroke)
      for (std::size_t i = 0; i < pts.size(); ++i)
        stroke_segment(image, pts[i], pts[(i + 1) % pts.size()], p.stroke_width * scale, linear(*p.stroke));
  }
  for (const Drawing::Dot& c : d.dots) fill_disc(image, to_pixels(c.centre), c.radius * scale, linear(c.fill));
  // The bitmap font's 16-pixel cell matches a 15-unit sans-serif font; its baseline is 4 pixels
  // above the cell's bottom.
  const int text_scale = std::max(1, static_cast<int>(std::lround(d.font_size * scale / 15.0)));
  for (const Drawing::Text& t : d.texts) {
    const glm::dvec2 at = to_pixels(t.baseline_left);
    draw_text(image, static_cast<int>(std::lround(at.x)),
              static_cast<int>(std::lround(at.y)) - (text_line_height(1) - 4) * text_scale, t.text, linear(t.colour),
              text_scale);
  }
  return image;
}

}  // namespace tessim::render
