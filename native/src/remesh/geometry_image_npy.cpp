// NumPy .npy files (format versions 1 and 2) holding an (n+1, n+1, 3) array.
#include <cstdint>
#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>

#include "consistent_maps/errors.h"
#include "consistent_maps/geometry_image.h"
#include "remesh/image_size.h"

namespace cmaps {
namespace {

const char kMagic[] = "\x93NUMPY";

}  // namespace

void write_geometry_image_npy(const std::string& path, const GeometryImage& image) {
  check_image_size(image);
  const int side = image.n + 1;
  std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (" + std::to_string(side) + ", " +
                       std::to_string(side) + ", 3), }";
  // Pad with spaces to a newline-terminated header ending on a 64-byte boundary.
  const size_t preamble = 10;
  header.append(63 - (preamble + header.size()) % 64, ' ');
  header += '\n';
  std::ofstream out(path, std::ios::binary);
  out.write(kMagic, 6);
  const unsigned char version_and_length[4] = {1, 0, static_cast<unsigned char>(header.size() & 0xff),
                                               static_cast<unsigned char>(header.size() >> 8)};
  out.write(reinterpret_cast<const char*>(version_and_length), 4);
  out << header;
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 is three packed doubles");
  // Little-endian host assumed, as on every platform the library targets.
  out.write(reinterpret_cast<const char*>(image.pixels.data()), image.pixels.size() * sizeof(Vec3));
  if (!out) throw IoError("cannot write " + path);
}

GeometryImage read_geometry_image_npy(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot open " + path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string data = buffer.str();
  auto fail = [&](const std::string& why) { return IoError(path + ": " + why); };
  if (data.size() < 10 || data.compare(0, 6, kMagic, 6) != 0) throw fail("not a .npy file");
  const auto byte = [&](size_t k) { return static_cast<size_t>(static_cast<unsigned char>(data[k])); };
  size_t header_start = 10, header_length = byte(8) | byte(9) << 8;
  if (byte(6) >= 2) {
    if (data.size() < 12) throw fail("truncated header");
    header_start = 12;
    header_length = byte(8) | byte(9) << 8 | byte(10) << 16 | byte(11) << 24;
  }
  if (data.size() < header_start + header_length) throw fail("truncated header");
  const std::string header = data.substr(header_start, header_length);
  std::smatch descr, shape;
  if (!std::regex_search(header, descr, std::regex("'descr':\\s*'([<|]f[48])'")))
    throw fail("expected little-endian float32 or float64 data");
  if (std::regex_search(header, std::regex("'fortran_order':\\s*True"))) throw fail("Fortran order is not supported");
  const std::regex shape_pattern("'shape':\\s*\\(\\s*(\\d{1,9})\\s*,\\s*(\\d{1,9})\\s*,\\s*3\\s*,?\\s*\\)");
  if (!std::regex_search(header, shape, shape_pattern))
    throw fail("expected shape (n+1, n+1, 3)");
  const long side = std::stol(shape[1]);
  if (side != std::stol(shape[2]) || side < 3 || side % 2 == 0 || side > 46341)
    throw fail("expected a square image of odd side >= 3, got " + std::string(shape[1]) + " x " +
               std::string(shape[2]));
  const bool single = descr[1].str().back() == '4';
  const size_t count = static_cast<size_t>(side) * side * 3, width = single ? 4 : 8;
  const size_t offset = header_start + header_length;
  if (data.size() < offset + count * width) throw fail("truncated data");
  GeometryImage image;
  image.n = static_cast<int>(side - 1);
  image.pixels.resize(static_cast<size_t>(side) * side);
  for (size_t k = 0; k < count; ++k) {
    double value;
    if (single) {
      float f;
      std::memcpy(&f, data.data() + offset + k * 4, 4);
      value = f;
    } else {
      std::memcpy(&value, data.data() + offset + k * 8, 8);
    }
    image.pixels[k / 3][k % 3] = value;
  }
  return image;
}

}  // namespace cmaps
