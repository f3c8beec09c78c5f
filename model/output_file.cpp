#include "model/output_file.hpp"

#include <unistd.h>

#include <system_error>

#include "model/error.hpp"

namespace tessim {

AtomicOutput::AtomicOutput(std::filesystem::path target, bool binary) : target_(std::move(target)) {
  temp_ = target_;
  temp_ += ".tmp-" + std::to_string(::getpid());
  out_.open(temp_, binary ? std::ios::out | std::ios::binary | std::ios::trunc
                          : std::ios::out | std::ios::trunc);
  if (!out_) throw InputError(target_.string(), "output", "cannot open for writing");
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) {
    out_.close();
    std::error_code ec;
    std::filesystem::remove(temp_, ec);
  }
}

void AtomicOutput::commit() {
  out_.flush();
  if (!out_) throw InputError(target_.string(), "output", "write failed");
  out_.close();
  commit_external();
}

void AtomicOutput::commit_external() {
  if (out_.is_open()) out_.close();
  std::error_code ec;
  std::filesystem::rename(temp_, target_, ec);
  if (ec) throw InputError(target_.string(), "output", "cannot move into place: " + ec.message());
  committed_ = true;
}

}  // namespace tessim
