#pragma once
// Texture images: reading PNG and BMP through stb_image (with our own checks first), and our
// own readers for what stb lacks: RLE BMP, PNM (P1-P6), XBM and XPM; writing PNG
// (stb_image_write).
// Errors are IoErrors naming the file, the line for the text formats, and the reason.
#include <cstdint>
#include <string>
#include <vector>

namespace trilab {

/// 8-bit RGBA pixels, rows from top to bottom.
struct Image {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;  ///< width * height * 4 bytes
    bool empty() const { return width == 0 || height == 0; }
};

/// Extensions read_image() accepts (lower case, without the dot).
std::vector<std::string> supported_image_extensions();
/// Reads any supported image, chosen by extension (case-insensitive). Throws IoError.
///
/// Variants: PNG (any bit depth and colour type stb_image reads); BMP 1/4/8/16/24/32 bit,
/// uncompressed or bitfields, bottom-up or top-down, and RLE8 / RLE4 (our reader; pixels the
/// data skips stay transparent black); PNM P1-P6 under .pnm, .ppm, .pgm or .pbm, maxval up to
/// 65535 scaled to 8 bits; XBM (X11 char or X10 short bits, 1 = black); XPM3 (1-8 characters
/// per pixel, #RGB to #RRRRGGGGBBBB scaled to 8 bits, every X11 colour name of x11-common's
/// rgb.txt ignoring case and spaces, None = transparent; the c key is used, else g, g4, m).
/// Budget: at most 32768 pixels a side and 64 Mpixel (2^26 pixels, 256 MiB as RGBA), and the
/// decoding (the RGBA image, a decoder buffer of the same size and a PNG's inflated data)
/// within half the memory available now; sizes over these, and sizes the file cannot hold,
/// are refused from the header, with the numbers, before anything of the image's size is
/// allocated. A PNG's image data is inflated once, bounded, before it is decoded: data that
/// inflates past the size its header declares (or ends before it, or is corrupt) is refused.
/// Binary PNM may carry bytes after the raster (a Netpbm stream of several images: the first
/// is read); the text formats must hold exactly the declared pixels.
Image read_image(const std::string& path);
/// Reads an image whose whole file is already in memory; the format is chosen by the
/// extension of `name`, which also labels the errors. (read_image reads the file and calls
/// this; the fuzzers call it directly.) Throws IoError.
Image read_image_bytes(const std::string& bytes, const std::string& name);
/// Writes a PNG through a temporary file and a rename. Throws IoError.
void write_png(const Image& image, const std::string& path);
/// A checkerboard of `squares` x `squares` alternating light and dark squares.
Image make_checkerboard(int size = 512, int squares = 8);

}  // namespace trilab
