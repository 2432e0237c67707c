// Library version, reported by `cmaps --version` and the Python module.
// Keep in step with project(VERSION) in CMakeLists.txt and blender_manifest.toml.
#pragma once

namespace cmaps {

inline constexpr const char* kVersion = "0.1.0";

}  // namespace cmaps
