#pragma once
// An RGB picture in memory and its PNG file (libpng): what renders produce and tests read back.

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace graspkit {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // 3 bytes a pixel, rows top to bottom

  Image() = default;
  Image(int width, int height, std::array<std::uint8_t, 3> fill = {255, 255, 255});

  std::array<std::uint8_t, 3> pixel(int x, int y) const;
  void setPixel(int x, int y, std::array<std::uint8_t, 3> colour);
};

// Writes `image` as an 8-bit RGB PNG, atomically (a temporary file, then a rename). Throws
// graspkit::Error naming the file when it cannot be written or the image is empty.
void writePng(const Image& image, const std::filesystem::path& file);
// The same PNG's bytes, for a server to send. Throws graspkit::Error for an empty image.
std::string pngBytes(const Image& image);
// Reads an 8-bit or 16-bit PNG of any colour type into RGB (alpha dropped, grey expanded).
// Throws graspkit::Error naming the file for a missing or damaged file.
Image readPng(const std::filesystem::path& file);

// Tiles `images` row by row, `columns` to a row, into one picture with `gap` pixels of `fill`
// between them; every tile takes the size of the largest. Empty for no images.
Image tileImages(std::span<const Image> images, int columns, int gap = 4,
                 std::array<std::uint8_t, 3> fill = {255, 255, 255});

}  // namespace graspkit
