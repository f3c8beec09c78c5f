// The image-output plugin: PNG and OpenEXR through OpenImageIO behind the C interface of
// imageio_plugin.h. Built as a module that only the CLI's image writer loads.
#include "render/imageio/imageio_plugin.h"

#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <exception>
#include <memory>
#include <string>

struct tessim_image_out {
  std::unique_ptr<OIIO::ImageOutput> out;
  bool closed = false;
};

namespace {

int report(char* err, size_t err_size, const std::string& reason) {
  if (err && err_size > 0) std::snprintf(err, err_size, "%s", reason.c_str());
  return 1;
}

}  // namespace

extern "C" {

int tessim_imageio_abi_version(void) { return TESSIM_IMAGEIO_ABI_VERSION; }

int tessim_image_open(const char* path, int png, int width, int height, tessim_image_out** out,
                      char* err, size_t err_size) {
  try {
    auto handle = std::make_unique<tessim_image_out>();
    handle->out = OIIO::ImageOutput::create(png ? "png" : "openexr");
    if (!handle->out) return report(err, err_size, "OpenImageIO has no writer for this format: " + OIIO::geterror());
    OIIO::ImageSpec spec(width, height, 3, png ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::HALF);
    spec.attribute("oiio:ColorSpace", png ? "sRGB" : "Linear");
    if (!handle->out->open(path, spec)) return report(err, err_size, handle->out->geterror());
    *out = handle.release();
    return 0;
  } catch (const std::exception& e) {
    return report(err, err_size, e.what());
  }
}

int tessim_image_write_rows(tessim_image_out* out, int y_begin, int rows, const float* rgb, char* err,
                            size_t err_size) {
  try {
    if (!out->out->write_scanlines(y_begin, y_begin + rows, 0, OIIO::TypeDesc::FLOAT, rgb))
      return report(err, err_size, out->out->geterror());
    return 0;
  } catch (const std::exception& e) {
    return report(err, err_size, e.what());
  }
}

int tessim_image_close(tessim_image_out* out, char* err, size_t err_size) {
  try {
    if (out->closed) return 0;
    out->closed = true;
    if (!out->out->close()) return report(err, err_size, out->out->geterror());
    return 0;
  } catch (const std::exception& e) {
    return report(err, err_size, e.what());
  }
}

void tessim_image_free(tessim_image_out* out) { delete out; }

}  // extern "C"
