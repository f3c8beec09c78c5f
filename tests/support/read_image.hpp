// Reads a written PNG or EXR back as linear float RGB (OpenImageIO), for tests of pictures.
#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

#include <OpenImageIO/imageio.h>

namespace tessim::testing {

struct ReadBack {
  int width = 0, height = 0;
  std::vector<float> rgb;  // row-major, top row first; empty when the file could not be read

  const float* pixel(int x, int y) const { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
};

inline ReadBack read_back(const std::filesystem::path& path) {
  ReadBack r;
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) return r;
  r.width = in->spec().width;
  r.height = in->spec().height;
  r.rgb.resize(static_cast<std::size_t>(r.width) * r.height * 3);
  if (in->spec().nchannels != 3 || !in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, r.rgb.data())) r = {};
  return r;
}

}  // namespace tessim::testing
