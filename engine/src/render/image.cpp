// PNG through libpng: encoded into memory, then written with writeFileAtomically, so a render
// never leaves half a picture behind.
#include "graspkit/render/image.hpp"

#include <algorithm>
#include <csetjmp>
#include <fstream>
#include <iterator>
#include <string>

#include <fmt/format.h>
#include <png.h>

#include "graspkit/base/error.hpp"
#include "graspkit/base/output_file.hpp"

namespace graspkit {

Image::Image(int w, int h, std::array<std::uint8_t, 3> fill) : width(w), height(h) {
  if (w < 0 || h < 0) throw Error(fmt::format("an image cannot be {}x{} pixels", w, h));
  rgb.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
  for (std::size_t i = 0; i < rgb.size(); i += 3) std::copy(fill.begin(), fill.end(), &rgb[i]);
}

std::array<std::uint8_t, 3> Image::pixel(int x, int y) const {
  const std::size_t at = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                          static_cast<std::size_t>(x)) *
                         3;
  return {rgb.at(at), rgb.at(at + 1), rgb.at(at + 2)};
}

void Image::setPixel(int x, int y, std::array<std::uint8_t, 3> colour) {
  if (x < 0 || y < 0 || x >= width || y >= height) return;
  const std::size_t at = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                          static_cast<std::size_t>(x)) *
                         3;
  std::copy(colour.begin(), colour.end(), &rgb[at]);
}

namespace {

// libpng reports errors by longjmp; the message is kept here so it can become an Error after
// the jump, outside libpng.
struct PngState {
  std::string error;
  std::string encoded;
  const std::string* input = nullptr;
  std::size_t readAt = 0;
};

void onPngError(png_structp png, png_const_charp message) {
  static_cast<PngState*>(png_get_error_ptr(png))->error = message;
  png_longjmp(png, 1);
}

void onPngWarning(png_structp, png_const_charp) {}

void appendEncoded(png_structp png, png_bytep data, png_size_t length) {
  auto& state = *static_cast<PngState*>(png_get_io_ptr(png));
  state.encoded.append(reinterpret_cast<const char*>(data), length);
}

void flushNothing(png_structp) {}

void readEncoded(png_structp png, png_bytep data, png_size_t length) {
  auto& state = *static_cast<PngState*>(png_get_io_ptr(png));
  if (state.readAt + length > state.input->size()) png_error(png, "the file ends too early");
  std::copy_n(state.input->data() + state.readAt, length, reinterpret_cast<char*>(data));
  state.readAt += length;
}

std::string encodePng(const Image& image, PngState& state) {
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, onPngError, onPngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    throw Error("cannot start a PNG encoder (out of memory)");
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return {};
  }
  png_set_write_fn(png, &state, appendEncoded, flushNothing);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y) {
    png_write_row(png, &image.rgb[static_cast<std::size_t>(y) * image.width * 3]);
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return std::move(state.encoded);
}

}  // namespace

void writePng(const Image& image, const std::filesystem::path& file) {
  if (image.width <= 0 || image.height <= 0)
    throw Error(SourceLocation{file.string(), 0, {}}, "cannot write an empty picture");
  PngState state;
  const std::string encoded = encodePng(image, state);
  if (!state.error.empty())
    throw Error(SourceLocation{file.string(), 0, {}}, "cannot encode the PNG: " + state.error);
  writeFileAtomically(file, encoded);
}

std::string pngBytes(const Image& image) {
  if (image.width <= 0 || image.height <= 0) throw Error("cannot encode an empty picture");
  PngState state;
  std::string encoded = encodePng(image, state);
  if (!state.error.empty()) throw Error("cannot encode the PNG: " + state.error);
  return encoded;
}

namespace {

// The libpng calls of a read, apart from any C++ object a longjmp could skip; false after a
// libpng error (the message is in state.error).
bool decodePng(png_structp png, png_infop info, PngState& state, Image* image) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_read_fn(png, &state, readEncoded);
  png_read_info(png, info);
  png_set_strip_16(png);
  png_set_strip_alpha(png);
  png_set_palette_to_rgb(png);
  png_set_expand_gray_1_2_4_to_8(png);
  png_set_gray_to_rgb(png);
  png_read_update_info(png, info);
  const png_uint_32 width = png_get_image_width(png, info);
  const png_uint_32 height = png_get_image_height(png, info);
  if (width > 1u << 15 || height > 1u << 15) png_error(png, "the picture is too large");
  *image = Image(static_cast<int>(width), static_cast<int>(height));
  for (png_uint_32 y = 0; y < height; ++y) {
    png_read_row(png, &image->rgb[static_cast<std::size_t>(y) * width * 3], nullptr);
  }
  png_read_end(png, nullptr);
  return true;
}

}  // namespace

Image readPng(const std::filesystem::path& file) {
  const SourceLocation where{file.string(), 0, {}};
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(where, "cannot open the picture");
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8))
    throw Error(where, "not a PNG file");
  PngState state;
  state.input = &bytes;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, onPngError, onPngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    throw Error(where, "cannot start a PNG decoder (out of memory)");
  }
  Image image;
  const bool decoded = decodePng(png, info, state, &image);
  png_destroy_read_struct(&png, &info, nullptr);
  if (!decoded) throw Error(where, "damaged PNG: " + state.error);
  return image;
}

Image tileImages(std::span<const Image> images, int columns, int gap,
                 std::array<std::uint8_t, 3> fill) {
  if (images.empty()) return {};
  columns = std::clamp(columns, 1, static_cast<int>(images.size()));
  const int rows = (static_cast<int>(images.size()) + columns - 1) / columns;
  int tileWidth = 0;
  int tileHeight = 0;
  for (const Image& image : images) {
    tileWidth = std::max(tileWidth, image.width);
    tileHeight = std::max(tileHeight, image.height);
  }
  Image sheet(columns * tileWidth + (columns - 1) * gap, rows * tileHeight + (rows - 1) * gap,
              fill);
  for (std::size_t i = 0; i < images.size(); ++i) {
    const int left = static_cast<int>(i) % columns * (tileWidth + gap);
    const int top = static_cast<int>(i) / columns * (tileHeight + gap);
    for (int y = 0; y < images[i].height; ++y)
      for (int x = 0; x < images[i].width; ++x)
        sheet.setPixel(left + x, top + y, images[i].pixel(x, y));
  }
  return sheet;
}

}  // namespace graspkit
