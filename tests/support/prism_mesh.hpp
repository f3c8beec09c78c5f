// A closed 16-sided prism with a ring of vertices halfway up, as OBJ text without normals: 50
// vertices, 96 triangles; its two rims are hard edges (90°), its sides smooth (22.5° between
// neighbouring side faces). The scalar-tagged import makes its 32 rim vertices crease vertices.
#pragma once

#include <cmath>
#include <sstream>
#include <string>

namespace tessim::testing {

inline std::string prism_obj() {
  std::ostringstream s;
  s.precision(17);
  const int n = 16;
  for (int ring = 0; ring < 3; ++ring)
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * 3.14159265358979323846 * i / n;
      s << "v " << static_cast<float>(std::cos(a)) << " " << static_cast<float>(std::sin(a)) << " " << ring - 1 << "\n";
    }
  s << "v 0 0 -1\nv 0 0 1\n";  // centres of the bottom (49) and top (50) caps, 1-based
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    for (int ring = 0; ring < 2; ++ring) {
      const int a = ring * n + i + 1, b = ring * n + j + 1, c = (ring + 1) * n + j + 1, d = (ring + 1) * n + i + 1;
      s << "f " << a << " " << b << " " << c << "\nf " << a << " " << c << " " << d << "\n";
    }
    s << "f " << 3 * n + 1 << " " << j + 1 << " " << i + 1 << "\n";                  // bottom, facing -z
    s << "f " << 3 * n + 2 << " " << 2 * n + i + 1 << " " << 2 * n + j + 1 << "\n";  // top, facing +z
  }
  return s.str();
}

}  // namespace tessim::testing
