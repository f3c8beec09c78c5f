// C interface of the image-output plugin (tessim_imageio), the only code that links
// OpenImageIO. The CLI loads it with dlopen when it writes an image, so that the commands that
// write none (sim, info, cosim, ...) do not pay for loading OpenImageIO's ~260 shared libraries
// at start-up (docs/images.md, "Image output").
//
// Every function returns 0 on success; on failure it returns non-zero and writes a
// NUL-terminated reason into err[0..err_size).
#pragma once

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

// Bumped whenever a signature below changes; the loader refuses a plugin of another version.
#define TESSIM_IMAGEIO_ABI_VERSION 1

typedef struct tessim_image_out tessim_image_out;

int tessim_imageio_abi_version(void);

// Opens `path` for an RGB image of width x height. `png` != 0: 8-bit sRGB PNG (the caller
// passes sRGB-encoded values); 0: half-float linear OpenEXR. The format is named explicitly
// because the caller writes a temporary file whose name has no image extension.
int tessim_image_open(const char* path, int png, int width, int height, tessim_image_out** out,
                      char* err, size_t err_size);
// Rows [y_begin, y_begin + rows) as width x rows x 3 floats, rows in order.
int tessim_image_write_rows(tessim_image_out* out, int y_begin, int rows, const float* rgb,
                            char* err, size_t err_size);
// Closes the file (flushing it); the handle stays valid until tessim_image_free.
int tessim_image_close(tessim_image_out* out, char* err, size_t err_size);
void tessim_image_free(tessim_image_out* out);

#ifdef __cplusplus
}
#endif
