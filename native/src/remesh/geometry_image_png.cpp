// 16-bit RGB PNG geometry images. The zlib stream uses stored (uncompressed)
// deflate blocks: no compression library is needed, and float geometry
// barely compresses anyway.
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "consistent_maps/errors.h"
#include "consistent_maps/geometry_image.h"
#include "remesh/image_size.h"

namespace cmaps {
namespace {

const char kSignature[] = "\x89PNG\r\n\x1a\n";
const char kBoundsKey[] = "cmaps_bbox";

uint32_t crc32(const std::string& bytes) {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t n = 0; n < 256; ++n) {
      uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  uint32_t c = 0xffffffffu;
  for (unsigned char b : bytes) c = table[(c ^ b) & 0xff] ^ (c >> 8);
  return c ^ 0xffffffffu;
}

uint32_t adler32(const std::string& bytes) {
  uint32_t a = 1, b = 0;
  for (unsigned char x : bytes) a = (a + x) % 65521, b = (b + a) % 65521;
  return b << 16 | a;
}

void put32(std::string& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>(v >> shift & 0xff);
}

uint32_t get32(const std::string& in, size_t at) {
  uint32_t v = 0;
  for (size_t k = 0; k < 4; ++k) v = v << 8 | static_cast<unsigned char>(in[at + k]);
  return v;
}

void put_chunk(std::string& out, const std::string& type, const std::string& data) {
  put32(out, static_cast<uint32_t>(data.size()));
  const std::string typed = type + data;
  out += typed;
  put32(out, crc32(typed));
}

std::string zlib_stored(const std::string& raw) {
  std::string z = "\x78\x01";  // deflate, 32K window, no dictionary; (0x78 * 256 + 1) % 31 == 0
  size_t at = 0;
  do {
    const size_t length = std::min<size_t>(65535, raw.size() - at);
    const bool last = at + length == raw.size();
    z += static_cast<char>(last ? 1 : 0);  // BFINAL, BTYPE 00 (stored), padding to the byte boundary
    z += static_cast<char>(length & 0xff), z += static_cast<char>(length >> 8);
    z += static_cast<char>(~length & 0xff), z += static_cast<char>((~length >> 8) & 0xff);
    z.append(raw, at, length);
    at += length;
  } while (at < raw.size());
  put32(z, adler32(raw));
  return z;
}

}  // namespace

void write_geometry_image_png(const std::string& path, const GeometryImage& image) {
  check_image_size(image);
  const uint32_t side = image.n + 1;
  Vec3 lo = image.pixels[0], hi = image.pixels[0];
  for (const Vec3& p : image.pixels) {
    if (!p.allFinite()) throw InvalidInput("geometry image: pixel values must be finite");
    lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  std::string raw;
  raw.reserve(side * (1 + 6 * side));
  for (uint32_t i = 0; i < side; ++i) {
    raw += '\0';  // filter type 0 (none)
    for (uint32_t j = 0; j < side; ++j) {
      for (int c = 0; c < 3; ++c) {
        const double range = hi[c] - lo[c];
        const long q = range > 0 ? std::lround((image.at(i, j)[c] - lo[c]) / range * 65535) : 0;
        raw += static_cast<char>(q >> 8), raw += static_cast<char>(q & 0xff);
      }
    }
  }
  std::string header;
  put32(header, side), put32(header, side);
  header += std::string("\x10\x02\x00\x00\x00", 5);  // 16 bits, RGB, deflate, filter 0, no interlace
  char bounds[256];
  std::snprintf(bounds, sizeof bounds, "%.17g %.17g %.17g %.17g %.17g %.17g", lo[0], lo[1], lo[2], hi[0], hi[1],
                hi[2]);
  std::string png(kSignature, 8);
  put_chunk(png, "IHDR", header);
  put_chunk(png, "tEXt", std::string(kBoundsKey) + '\0' + bounds);
  put_chunk(png, "IDAT", zlib_stored(raw));
  put_chunk(png, "IEND", "");
  std::ofstream out(path, std::ios::binary);
  out << png;
  if (!out) throw IoError("cannot write " + path);
}

GeometryImage read_geometry_image_png(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot open " + path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string png = buffer.str();
  auto fail = [&](const std::string& why) { return IoError(path + ": " + why); };
  if (png.compare(0, 8, kSignature, 8) != 0) throw fail("not a PNG file");

  std::string header, zlib, bounds;
  for (size_t at = 8;;) {
    if (at + 12 > png.size()) throw fail("truncated PNG");
    const uint32_t length = get32(png, at);
    if (length > png.size() - at - 12) throw fail("truncated PNG");
    const std::string typed = png.substr(at + 4, 4 + length);
    if (crc32(typed) != get32(png, at + 8 + length)) throw fail("corrupt PNG chunk (CRC mismatch)");
    const std::string type = typed.substr(0, 4), data = typed.substr(4);
    at += 12 + length;
    if (type == "IHDR") header = data;
    if (type == "IDAT") zlib += data;
    if (type == "tEXt" && data.compare(0, sizeof kBoundsKey, std::string(kBoundsKey) + '\0') == 0)
      bounds = data.substr(sizeof kBoundsKey);
    if (type == "IEND") break;
  }
  if (header.size() != 13) throw fail("missing PNG header");
  const uint32_t side = get32(header, 0);
  if (side != get32(header, 4) || side < 3 || side % 2 == 0 || side > 46341)
    throw fail("expected a square image of odd side >= 3");
  if (header.compare(8, 5, std::string("\x10\x02\x00\x00\x00", 5)) != 0)
    throw fail("expected a 16-bit RGB, non-interlaced PNG");
  Vec3 lo, hi;
  if (std::sscanf(bounds.c_str(), "%lf %lf %lf %lf %lf %lf", &lo[0], &lo[1], &lo[2], &hi[0], &hi[1], &hi[2]) != 6)
    throw fail("no cmaps bounding box (tEXt chunk 'cmaps_bbox'); not a cmaps geometry image");

  // Inflate stored blocks only: what the writer produces.
  if (zlib.size() < 6 || (static_cast<unsigned char>(zlib[0]) & 0x0f) != 8) throw fail("bad zlib stream");
  std::string raw;
  size_t at = 2;
  for (bool last = false; !last;) {
    if (at + 5 > zlib.size()) throw fail("truncated zlib stream");
    const unsigned char block = zlib[at];
    last = block & 1;
    if ((block >> 1 & 3) != 0)
      throw fail("compressed PNG data; only uncompressed PNGs as written by cmaps can be read");
    const size_t length = static_cast<unsigned char>(zlib[at + 1]) | static_cast<unsigned char>(zlib[at + 2]) << 8;
    if (at + 5 + length > zlib.size()) throw fail("truncated zlib stream");
    raw.append(zlib, at + 5, length);
    at += 5 + length;
  }
  if (at + 4 > zlib.size() || get32(zlib, at) != adler32(raw)) throw fail("corrupt zlib stream (checksum mismatch)");
  const size_t row = 1 + 6 * static_cast<size_t>(side);
  if (raw.size() != row * side) throw fail("image data has the wrong size");

  GeometryImage image;
  image.n = static_cast<int>(side - 1);
  image.pixels.resize(static_cast<size_t>(side) * side);
  for (size_t i = 0; i < side; ++i) {
    if (raw[i * row] != 0) throw fail("PNG row filters are not supported");
    for (size_t j = 0; j < side; ++j)
      for (int c = 0; c < 3; ++c) {
        const size_t k = i * row + 1 + 6 * j + 2 * c;
        const int q = static_cast<unsigned char>(raw[k]) << 8 | static_cast<unsigned char>(raw[k + 1]);
        const double t = q / 65535.0;  // this form gives back lo and hi exactly
        image.pixels[i * side + j][c] = (1 - t) * lo[c] + t * hi[c];
      }
  }
  return image;
}

}  // namespace cmaps
