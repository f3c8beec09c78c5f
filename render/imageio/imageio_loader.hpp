// Loads the image-output plugin (imageio_plugin.h) on first use. The plugin is looked up as
// $TESSIM_IMAGEIO_PLUGIN if set, else as ../lib/tessim/tessim_imageio.so beside the running
// executable (the layout of both the build tree and `cmake --install`).
#pragma once

#include <filesystem>

#include "render/imageio/imageio_plugin.h"

namespace tessim::render {

struct ImageIoPlugin {
  decltype(&tessim_image_open) open = nullptr;
  decltype(&tessim_image_write_rows) write_rows = nullptr;
  decltype(&tessim_image_close) close = nullptr;
  decltype(&tessim_image_free) free = nullptr;
};

// The loaded plugin (loaded once per process, never unloaded). Throws InputError naming
// `output` (the image the caller was about to write) when the plugin cannot be loaded.
const ImageIoPlugin& image_io_plugin(const std::filesystem::path& output);

// Where the plugin is looked up (for messages and tests).
std::filesystem::path image_io_plugin_path();

}  // namespace tessim::render
