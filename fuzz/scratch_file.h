#pragma once
/// The loaders read files: each fuzzing process writes its input to a scratch file of its own.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace tumble::fuzz {

/// Writes `size` bytes to "<tmp>/tumble_<stem>_<pid><extension>" and returns its path.
inline std::string writeScratch(const char* stem, const char* extension, const std::uint8_t* data,
                                std::size_t size) {
    const std::string path =
        (std::filesystem::temp_directory_path() /
         ("tumble_" + std::string(stem) + "_" + std::to_string(getpid()) + extension))
            .string();
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return path;
}

}  // namespace tumble::fuzz
