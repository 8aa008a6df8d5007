// Decoding and encoding of glTF texture images (image/jpeg, image/png) for the
// texture transfer, over the system libjpeg-turbo (libjpeg API) and libpng.
//
// The decoders are meant for untrusted bytes: bad input gives a non-OK Status with
// a one-line message ("corrupt JPEG: ...", "corrupt PNG: ..."), never a crash, and
// an image is refused (kResourceLimit) from its header, before its pixels are
// allocated, when a side exceeds kMaxImageSide or width * height * channels exceeds
// kMaxImageBytes. Sample values are returned as stored: glTF 2.0 says colour-space
// information in PNG and JPEG files (gAMA, iCCP, ICC profiles) must be ignored, so
// none of it is applied.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/status.h"

namespace eqmesh::texture {

// Largest width or height accepted by the decoders and the encoders.
constexpr int kMaxImageSide = 16384;
// Largest width * height * channels accepted (1 GiB of 8-bit samples).
constexpr uint64_t kMaxImageBytes = uint64_t{1} << 30;
// Most scans a JPEG may have. Progressive scripts use 6-12 (jpegtran's and
// mozjpeg's under 20) and every scan revisits the whole image, so more is a file
// built to keep the decoder busy.
constexpr int kMaxJpegScans = 256;

// An 8-bit image. channels: 1 gray, 2 gray + alpha, 3 RGB, 4 RGBA. Pixels are
// row-major, top row first, channels interleaved: width * height * channels bytes.
struct Image {
  int width = 0, height = 0;
  int channels = 0;
  std::vector<uint8_t> pixels;
};

enum class ImageFormat { kJpeg, kPng };

// The format named by the leading magic bytes (PNG signature, JPEG SOI + marker).
// kParseError for anything else, empty input included.
StatusOr<ImageFormat> SniffImageFormat(const uint8_t* data, size_t size);

// Decodes a PNG or JPEG (by magic bytes) into 8-bit samples. A PNG whose file is too
// short to hold its declared image data (deflate inflates at most 1032:1) is refused
// before its pixels are allocated.
//  * JPEG: baseline, extended, progressive and arithmetic-coded; grayscale stays 1
//    channel, YCbCr/RGB gives 3. CMYK/YCCK and 12-bit files are kUnsupportedFeature.
//    Damaged or missing image data is an error, never gray filler: so is a file cut
//    anywhere before its EOI marker, EOI alone included, since libjpeg cannot tell
//    that from a progressive file that lost its last scans. Framing oddities libjpeg
//    works around (junk between markers, an unknown JFIF version or Adobe transform,
//    a bad ICC marker) are accepted. More than kMaxJpegScans scans is kResourceLimit.
//  * PNG: every bit depth and colour type. Palettes expand to RGB, tRNS to an alpha
//    channel, 16-bit samples round to 8 bits, Adam7 is de-interlaced; gray stays gray
//    (1 channel, 2 with alpha). Missing or damaged image data is an error; chunks
//    after the image data (IEND included) are not read.
// Errors: kParseError (corrupt or truncated), kUnsupportedFeature, kResourceLimit.
StatusOr<Image> DecodeImage(const uint8_t* data, size_t size);

// The IJG quality (1..100) whose scaled Annex K luminance table (libjpeg's
// jpeg_set_quality) is closest, in summed absolute difference, to the quantization
// table of the file's first (luma) component; exact for files libjpeg wrote. -1 when
// the bytes are not a JPEG whose header libjpeg can read.
int EstimateJpegQuality(const uint8_t* data, size_t size);

// Baseline JPEG with optimized Huffman tables at IJG `quality` (1..100): 4:2:0
// chroma below quality 90, 4:4:4 from 90 up (there, halved chroma resolution would
// be the largest error left). 1 channel gives a grayscale JPEG, 3 a YCbCr one; the
// alpha of 2- and 4-channel images is DROPPED (JPEG has no alpha), so they encode
// as 1 and 3.
// Deterministic: the same image and quality give the same bytes (integer DCT, no
// timestamps). kInvalidArgument for a malformed image or quality out of range.
StatusOr<std::vector<uint8_t>> EncodeJpeg(const Image& image, int quality);

// Lossless PNG of 1..4 channels at 8 bits, zlib level 8 (level 9 measured about 2x
// slower for 0.2-2 % smaller textures) with libpng's adaptive row filters.
// Deterministic: no tIME, text or other ancillary chunks. kInvalidArgument for a
// malformed image.
StatusOr<std::vector<uint8_t>> EncodePng(const Image& image);

}  // namespace eqmesh::texture
