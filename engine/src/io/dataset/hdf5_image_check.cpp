#include "io/dataset/hdf5_image_check.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <cstring>

#include "graspkit/base/error.hpp"

namespace graspkit {
namespace {

constexpr std::string_view kSuperblockSignature("\x89HDF\r\n\x1a\n", 8);
constexpr std::string_view kCollectionSignature = "GCOL";
constexpr std::size_t kCollectionHeader = 16;  // signature, version, 3 reserved, size (8)
constexpr std::size_t kObjectHeader = 16;      // index (2), references (2), reserved (4), size (8)

std::uint64_t littleEndian(std::string_view bytes, std::size_t at, std::size_t width) {
  std::uint64_t value = 0;
  for (std::size_t k = 0; k < width; ++k)
    value |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes[at + k])) << (8 * k);
  return value;
}

[[noreturn]] void refuse(const std::filesystem::path& file, const std::string& why) {
  throw Error(SourceLocation{file.string()}, why);
}

void checkSuperblock(std::string_view image, const std::filesystem::path& file) {
  if (image.size() < 16 || image.substr(0, 8) != kSuperblockSignature)
    refuse(file, "not an HDF5 file (no superblock at its start)");
  const int version = static_cast<unsigned char>(image[8]);
  // Versions 0 and 1 keep the two sizes at bytes 13 and 14; versions 2 and 3 at 9 and 10.
  const std::size_t at = version <= 1 ? 13 : 9;
  const int offsets = static_cast<unsigned char>(image[at]);
  const int lengths = static_cast<unsigned char>(image[at + 1]);
  if (offsets != 8 || lengths != 8)
    refuse(file, fmt::format("HDF5 superblock with {}-byte offsets and {}-byte lengths; only 8 "
                             "and 8 are read",
                             offsets, lengths));
}

void checkCollection(std::string_view image, std::size_t start, const std::filesystem::path& file) {
  const std::uint64_t size = littleEndian(image, start + 8, 8);
  if (size < kCollectionHeader || size > image.size() - start)
    refuse(file, fmt::format("HDF5 global heap at byte {} says it holds {} bytes, past the "
                             "file's end",
                             start, size));
  const std::size_t end = start + size;
  for (std::size_t at = start + kCollectionHeader; at + kObjectHeader <= end;) {
    const std::uint64_t index = littleEndian(image, at, 2);
    if (index == 0) return;  // the free space: the rest of the collection
    const std::uint64_t bytes = littleEndian(image, at + 8, 8);
    if (bytes > end - at - kObjectHeader)
      refuse(file, fmt::format("HDF5 global heap at byte {}: object {} says it holds {} bytes, "
                               "more than its heap holds",
                               start, index, bytes));
    at += kObjectHeader + (bytes + 7) / 8 * 8;
  }
}

}  // namespace

void checkHdf5Image(std::string_view image, const std::filesystem::path& file) {
  checkSuperblock(image, file);
  for (std::size_t at = image.find(kCollectionSignature); at != std::string_view::npos;
       at = image.find(kCollectionSignature, at + 1)) {
    if (image.size() - at < kCollectionHeader) break;
    if (image[at + 4] != 1) continue;  // libhdf5 refuses any other version itself
    checkCollection(image, at, file);
  }
}

}  // namespace graspkit
