// Greyscale PNG height fields through libpng. libpng reports errors by longjmp, which must not
// cross a C++ object with a destructor: decode() holds only plain locals and writes into a
// Decoded that its caller owns, and the caller turns a failure into an InvalidArgument.

#include <cmath>
#include <cstdio>
#include <cstring>

#include "mesh_io_parts.h"

#ifdef TUMBLE_HAVE_PNG
#include <png.h>

#include <csetjmp>
#endif

namespace tumble {

#ifdef TUMBLE_HAVE_PNG
namespace {

/// What decode() reads, and the input it reads from.
struct Decoded {
    const std::string* bytes = nullptr;
    std::size_t read = 0;  // bytes consumed by libpng
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    int bitDepth = 0;
    int colorType = 0;
    std::vector<std::uint8_t> pixels;  // row by row, top row first, 1 or 2 bytes per sample
    std::vector<std::uint8_t*> rows;   // into pixels, for png_read_image
    char error[256] = {};              // libpng's message, or ours, when decode() fails
};

void onError(png_structp png, png_const_charp message) {
    auto* out = static_cast<Decoded*>(png_get_error_ptr(png));
    std::snprintf(out->error, sizeof out->error, "%s", message);
    png_longjmp(png, 1);
}

void onWarning(png_structp, png_const_charp) {}  // e.g. a bad gamma chunk: heights ignore it

void readBytes(png_structp png, png_bytep data, png_size_t length) {
    auto* in = static_cast<Decoded*>(png_get_io_ptr(png));
    if (in->bytes->size() - in->read < length)
        png_error(png, "the file ends inside the image (truncated)");
    std::memcpy(data, in->bytes->data() + in->read, length);
    in->read += length;
}

/// Whether the header is one this loader takes; fills out->error when not.
bool acceptedHeader(Decoded* out) {
    if (out->colorType != PNG_COLOR_TYPE_GRAY || (out->bitDepth != 8 && out->bitDepth != 16)) {
        std::snprintf(out->error, sizeof out->error,
                      "a height field is an 8- or 16-bit greyscale image (got colour type %d, "
                      "%d bits per sample)",
                      out->colorType, out->bitDepth);
        return false;
    }
    if (std::size_t{out->width} * out->height > kMaxHeightFieldSamples) {
        std::snprintf(out->error, sizeof out->error,
                      "%u x %u pixels is more than the %zu samples a height field may have",
                      out->width, out->height, kMaxHeightFieldSamples);
        return false;
    }
    return true;
}

/// Reads the header and the pixels into `out`; false (with out->error) on any failure.
bool decode(Decoded* out) {
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, out, onError, onWarning);
    if (png == nullptr)
        return false;
    png_infop info = png_create_info_struct(png);
    if (info == nullptr || setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        return false;
    }
    png_set_read_fn(png, out, readBytes);
    png_read_info(png, info);
    out->width = png_get_image_width(png, info);
    out->height = png_get_image_height(png, info);
    out->bitDepth = png_get_bit_depth(png, info);
    out->colorType = png_get_color_type(png, info);
    const bool accepted = acceptedHeader(out);
    if (accepted) {
        png_set_interlace_handling(png);  // every pass writes into the same rows
        png_read_update_info(png, info);
        const std::size_t rowBytes = png_get_rowbytes(png, info);
        out->pixels.resize(rowBytes * out->height);
        out->rows.resize(out->height);
        for (std::uint32_t y = 0; y < out->height; ++y)
            out->rows[y] = out->pixels.data() + y * rowBytes;
        png_read_image(png, out->rows.data());
        png_read_end(png, nullptr);
    }
    png_destroy_read_struct(&png, &info, nullptr);
    return accepted;
}

}  // namespace

bool havePngLoader() {
    return true;
}

HeightFieldData loadHeightFieldPng(const std::string& path, Real spacingX, Real spacingY,
                                   Real heightScale, Real heightOffset) {
    if (!std::isfinite(heightScale) || !std::isfinite(heightOffset))
        fail(path, ": heightScale = ", heightScale, " and heightOffset = ", heightOffset,
             " must be finite (m)");
    const std::string bytes = mesh_io::readFile(path);
    if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8))
        fail(path, ": not a PNG file (no PNG signature)");
    Decoded image;
    image.bytes = &bytes;
    if (!decode(&image))
        fail(path, ": ", image.error[0] != 0 ? image.error : "libpng could not read the file");
    HeightFieldData field;
    field.columns = image.width;
    field.rows = image.height;
    field.spacingX = spacingX;
    field.spacingY = spacingY;
    field.heights.resize(std::size_t{image.width} * image.height);
    const int bytesPerSample = image.bitDepth / 8;
    const Real scale = heightScale / (image.bitDepth == 16 ? 65535.0 : 255.0);
    for (std::uint32_t y = 0; y < image.height; ++y) {
        const std::uint8_t* row =
            image.pixels.data() + std::size_t{y} * image.width * bytesPerSample;
        const std::size_t j = image.height - 1 - y;  // the top row is the far edge (largest y)
        for (std::uint32_t i = 0; i < image.width; ++i) {
            const std::uint8_t* p = row + std::size_t{i} * bytesPerSample;
            const unsigned value = bytesPerSample == 2 ? (p[0] << 8) | p[1] : p[0];  // big-endian
            field.heights[j * image.width + i] = heightOffset + scale * value;
        }
    }
    try {
        checkHeightField(field);
    } catch (const MeshElementError& e) {
        const std::size_t i = e.index() % image.width, j = e.index() / image.width;
        fail(path, ": pixel (", i, ", ", image.height - 1 - j, "): height ", e.rule());
    } catch (const InvalidArgument& e) {
        fail(path, ": ", e.what());
    }
    return field;
}

#else

bool havePngLoader() {
    return false;
}

HeightFieldData loadHeightFieldPng(const std::string& path, Real, Real, Real, Real) {
    fail(path, ": PNG height fields need libpng, which this build was configured without ",
         "(apt install libpng-dev, then configure again)");
}

#endif

}  // namespace tumble
