// The version of the tool that produced a result (statistics JSON: "tool"): `git describe
// --always --dirty --tags` of the source tree at build time, or "unknown" outside a checkout.
#pragma once

namespace tessim {

const char* tool_version();

}  // namespace tessim
