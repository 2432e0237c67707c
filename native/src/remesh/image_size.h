// Shared check for geometry image writers: the pixel count must match n.
#pragma once
#include <string>

#include "consistent_maps/errors.h"
#include "consistent_maps/geometry_image.h"

namespace cmaps {

inline void check_image_size(const GeometryImage& image) {
  if (image.n < 2 || image.n % 2 || image.pixels.size() != static_cast<size_t>(image.n + 1) * (image.n + 1))
    throw InvalidInput("geometry image: " + std::to_string(image.pixels.size()) + " pixels for n = " +
                       std::to_string(image.n) + " (n must be even and >= 2)");
}

}  // namespace cmaps
