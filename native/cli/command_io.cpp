#include "command_io.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>

#include "consistent_maps/errors.h"

namespace cmaps::cli {

std::string in_quotes(const std::string& name) { return JsonObject::quote(name); }

std::string lowercase_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

cmaps::ProgressCallback terminal_progress(bool enabled) {
  if (!enabled) return {};
  return [](double fraction, const std::string& stage) {
    std::fprintf(stderr, "\r%3d%% %-40.40s", int(100 * std::clamp(fraction, 0.0, 1.0)), stage.c_str());
    std::fflush(stderr);
    return true;
  };
}

void check_output_path(const std::string& path) {
  const std::string ext = lowercase_extension(path);
  if (ext != ".obj" && ext != ".ply" && ext != ".off")
    throw UsageError("output '" + path + "' must end in .obj, .ply or .off");
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    throw cmaps::IoError("cannot write '" + path + "': directory '" + parent.string() + "' does not exist");
}

void check_output_directory(const std::string& dir) {
  namespace fs = std::filesystem;
  if (fs::exists(dir)) {
    if (!fs::is_directory(dir)) throw cmaps::IoError("cannot write into '" + dir + "': it is not a directory");
    return;
  }
  const fs::path parent = fs::path(dir).parent_path();
  if (!parent.empty() && !fs::is_directory(parent))
    throw cmaps::IoError("cannot create '" + dir + "': directory '" + parent.string() + "' does not exist");
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream file(path, std::ios::binary);
  file << text << '\n';
  if (!file) throw cmaps::IoError("cannot write '" + path + "'");
}

cmaps::SphereOptions sphere_options(const Arguments& args) {
  cmaps::SphereOptions options;
  options.seed = args.seed;
  options.effort = args.effort;
  options.threads = args.threads;
  return options;
}

void add_settings(JsonObject& json, const Arguments& args) {
  json.add("seed", static_cast<unsigned long long>(args.seed))
      .add("effort", args.effort)
      .add("threads", args.threads)
      .add("output", args.output);
}

}  // namespace cmaps::cli
