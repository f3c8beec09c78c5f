// The image-output plugin: PNG and OpenEXR through OpenImageIO behind the C interface of
// imageio_plugin.h. Built as a module that only the CLI's image writer loads.
#include "render/imageio/imageio_plugin.h"

#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <vector>

struct tessim_image_out {
  std::unique_ptr<OIIO::ImageOutput> out;
  std::string path;
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
    handle->path = path;
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
    // OpenImageIO's PNG and EXR writers do not see a failed write (a full file system leaves an
    // empty or cut file and a successful close): the file must read back whole.
    const OIIO::ImageSpec spec = out->out->spec();
    auto in = OIIO::ImageInput::open(out->path);
    std::vector<unsigned char> pixels(static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height) * 3 * 2);
    if (!in || !in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT16, pixels.data())) {
      OIIO::geterror();  // clear OpenImageIO's pending global error
      return report(err, err_size, "write failed: the written image does not read back (no space left on the file system?)");
    }
    return 0;
  } catch (const std::exception& e) {
    return report(err, err_size, e.what());
  }
}

void tessim_image_free(tessim_image_out* out) { delete out; }

}  // extern "C"
