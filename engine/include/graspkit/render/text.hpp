#pragma once
// Captions on pictures: a small built-in bitmap font, so that no font file is needed.

#include <array>
#include <cstdint>
#include <string_view>

#include "graspkit/render/image.hpp"

namespace graspkit {

// Writes `text` with its top-left corner at (x, y) in a 5 x 7 pixel font, each font pixel
// `scale` x `scale` image pixels, glyphs 6 font pixels apart. The font has digits, letters
// (upper case drawn for lower), space and . , - + = # : ( ) / %; other characters draw as a
// box. Parts outside the image are clipped.
void drawText(Image& image, int x, int y, std::string_view text,
              std::array<std::uint8_t, 3> colour = {0, 0, 0}, int scale = 1);
// The width and height drawText takes for `text`.
std::array<int, 2> textSize(std::string_view text, int scale = 1);

}  // namespace graspkit
