// libFuzzer target: the PNG height-field loader (scene/mesh_io.h, libpng behind it) on arbitrary
// bytes. Each chunk's CRC is rewritten before loading, so mutations reach the chunks' contents
// instead of all failing the checksum. A refusal (InvalidArgument with a message) is the expected
// answer; a crash, undefined behaviour, a leak, another exception, a refusal without a message, or
// an accepted field whose own checks fail is a finding.

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "scratch_file.h"
#include "tumble/scene/mesh_io.h"

namespace {

[[noreturn]] void finding(const char* what) {
    std::fprintf(stderr, "png_height_field_fuzz: %s\n", what);
    std::abort();
}

/// CRC-32 as PNG defines it (ISO 3309, polynomial 0xEDB88320, reflected).
std::uint32_t crc32(const std::uint8_t* data, std::size_t size) {
    static const std::array<std::uint32_t, 256> table = [] {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t n = 0; n < 256; ++n) {
            std::uint32_t c = n;
            for (int k = 0; k < 8; ++k)
                c = (c & 1) != 0 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[n] = c;
        }
        return t;
    }();
    std::uint32_t c = 0xFFFFFFFFu;
    for (std::size_t i = 0; i < size; ++i)
        c = table[(c ^ data[i]) & 0xFF] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

/// Rewrites the CRC of every whole chunk after the 8-byte signature.
void fixCrcs(std::string& bytes) {
    auto* b = reinterpret_cast<std::uint8_t*>(bytes.data());
    std::size_t at = 8;
    while (at + 12 <= bytes.size()) {
        const std::size_t length = (std::size_t{b[at]} << 24) | (std::size_t{b[at + 1]} << 16) |
                                   (std::size_t{b[at + 2]} << 8) | b[at + 3];
        if (length > bytes.size() - at - 12)
            break;
        const std::uint32_t crc = crc32(b + at + 4, length + 4);  // type and data
        for (int k = 0; k < 4; ++k)
            b[at + 8 + length + k] = static_cast<std::uint8_t>(crc >> (24 - 8 * k));
        at += length + 12;
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::string bytes(reinterpret_cast<const char*>(data), size);
    fixCrcs(bytes);
    const std::string file = tumble::fuzz::writeScratch(
        "png_fuzz", ".png", reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    tumble::HeightFieldData field;
    try {
        field = tumble::loadHeightFieldPng(file, 0.5, 0.5, 2);
    } catch (const tumble::InvalidArgument& e) {
        if (std::string(e.what()).empty())
            finding("a refusal without a message");
        return 0;
    }
    try {
        tumble::checkHeightField(field);
    } catch (const tumble::InvalidArgument& e) {
        finding(e.what());  // accepted, yet its own checks refuse it
    }
    return 0;
}
