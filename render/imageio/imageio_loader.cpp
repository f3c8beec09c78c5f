#include "render/imageio/imageio_loader.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <mutex>
#include <string>
#include <system_error>

#include "model/base/error.hpp"

namespace tessim::render {

namespace {

struct LoadResult {
  ImageIoPlugin plugin;
  std::string error;  // empty when loaded
};

template <typename Fn>
bool resolve(void* handle, const char* name, Fn& fn, std::string& error) {
  fn = reinterpret_cast<Fn>(dlsym(handle, name));
  if (!fn) error = std::string("missing symbol ") + name;
  return fn != nullptr;
}

LoadResult load() {
  LoadResult r;
  const std::filesystem::path path = image_io_plugin_path();
  // RTLD_LOCAL: OpenImageIO's dependencies stay private to the plugin.
  void* handle = dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    r.error = "cannot load the image writer " + path.string() + ": " + (why ? why : "unknown reason");
    return r;
  }
  int (*version)() = nullptr;
  if (!resolve(handle, "tessim_imageio_abi_version", version, r.error)) return r;
  if (version() != TESSIM_IMAGEIO_ABI_VERSION) {
    r.error = "image writer " + path.string() + " has interface version " + std::to_string(version()) +
              ", expected " + std::to_string(TESSIM_IMAGEIO_ABI_VERSION) + " (stale build?)";
    return r;
  }
  ImageIoPlugin& p = r.plugin;
  if (!resolve(handle, "tessim_image_open", p.open, r.error) ||
      !resolve(handle, "tessim_image_write_rows", p.write_rows, r.error) ||
      !resolve(handle, "tessim_image_close", p.close, r.error) ||
      !resolve(handle, "tessim_image_free", p.free, r.error))
    r.error = "image writer " + path.string() + ": " + r.error;
  return r;
}

}  // namespace

std::filesystem::path image_io_plugin_path() {
  if (const char* env = std::getenv("TESSIM_IMAGEIO_PLUGIN"); env && *env) return env;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path dir = ec ? std::filesystem::current_path() : exe.parent_path();
  return (dir / ".." / "lib" / "tessim" / "tessim_imageio.so").lexically_normal();
}

const ImageIoPlugin& image_io_plugin(const std::filesystem::path& output) {
  static const LoadResult loaded = load();
  if (!loaded.error.empty()) throw InputError(output.string(), "image", loaded.error);
  return loaded.plugin;
}

}  // namespace tessim::render
