#pragma once
// Image files: float EXR and 8-bit PNG writers, and a reader for anything
// OpenImageIO reads, through core/image_codec.h (OIIO loaded on first use).
// Writers are atomic (temporary file in the target directory, then rename),
// so readers never see a half-written image. All failures throw
// sb::JobError naming the path and OpenImageIO's message (or why the codec
// module could not be loaded).
#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"

namespace sb::metrics::io {

// float32 EXR. Channel names: 1 -> Y, 2 -> Y A, 3 -> R G B, 4 -> R G B A;
// other counts are rejected.
void write_exr(const std::string& path, const core::ImageF& img);

// 8-bit PNG: each value clamped to [0,1] (NaN -> 0), times 255, rounded to
// nearest. No colour transform; 1 channel is grey, 2 grey+alpha, 3 RGB,
// 4 RGBA (alpha written as given, not un-premultiplied).
void write_png(const std::string& path, const core::ImageF& img);
// The byte write_png stores for a value: [0, 1] scaled to 0..255 and
// rounded half away from zero (std::lround), outside clamped, NaN 0.
uint8_t png_byte(float v);

// A pixel mask (one byte per pixel, row-major, nonzero = in) as a one-channel
// 8-bit PNG: 255 in, 0 out. Throws std::invalid_argument when mask.size()
// is not width * height.
void write_mask_png(const std::string& path, const std::vector<uint8_t>& mask, int width,
                    int height);

// First subimage of any file OpenImageIO reads, converted to float (8-bit
// values become v/255), every channel, alpha not premultiplied by OIIO.
core::ImageF read_image(const std::string& path);

}  // namespace sb::metrics::io
