#pragma once
/// The byte-level half of checkpoints (checkpoint.cpp): a Writer and a Reader with one
/// interface, so each record's fields are listed once (`fields(a, x.f, x.g, ...)`) and the same
/// list writes and reads. Everything is little-endian whatever the host: integers by width,
/// enums by their underlying type, bool as one byte (0 or 1), Real as its IEEE-754 bits, Eigen
/// fixed-size matrices in storage order, vectors as a u64 count and their elements.

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "tumble/collision/shape.h"
#include "tumble/core/error.h"
#include "tumble/core/math.h"

namespace tumble::checkpoint_io {

/// FNV-1a, 64 bits, over `bytes`.
inline std::uint64_t fnv1a(std::span<const std::uint8_t> bytes) {
    std::uint64_t hash = 0xcbf29ce484222325ull;
    for (const std::uint8_t b : bytes) {
        hash ^= b;
        hash *= 0x100000001b3ull;
    }
    return hash;
}

class Writer {
public:
    static constexpr bool kReading = false;
    void word(std::uint64_t value, int width) {
        for (int i = 0; i < width; ++i)
            bytes.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
    }
    /// A count of elements about to be written.
    std::size_t count(std::size_t n) {
        word(n, 8);
        return n;
    }
    std::vector<std::uint8_t> bytes;
    /// The triangle surfaces of the surface section, in its order: a shape that carries one is
    /// saved as its index here (checkpoint.cpp).
    std::vector<Shape> surfaces;
};

class Reader {
public:
    static constexpr bool kReading = true;
    Reader(std::span<const std::uint8_t> data, std::string source)
        : data_(data), source_(std::move(source)) {}
    std::uint64_t word(int width) {
        if (data_.size() - position_ < static_cast<std::size_t>(width))
            corrupt("payload ends early");
        std::uint64_t value = 0;
        for (int i = 0; i < width; ++i)
            value |= std::uint64_t{data_[position_ + i]} << (8 * i);
        position_ += static_cast<std::size_t>(width);
        return value;
    }
    /// A count of elements about to be read: each takes at least one byte, so a count larger
    /// than what is left is corrupt (and never allocates gigabytes).
    std::size_t count(std::size_t) {
        const std::uint64_t n = word(8);
        if (n > data_.size() - position_)
            corrupt("element count ", n, " exceeds the bytes left");
        return static_cast<std::size_t>(n);
    }
    bool atEnd() const { return position_ == data_.size(); }
    std::uint32_t world = 0;      ///< world tag given to the non-null ids read
    std::vector<Shape> surfaces;  ///< rebuilt from the surface section (see Writer::surfaces)
    template <typename... Parts>
    [[noreturn]] void corrupt(Parts&&... parts) const {
        fail("checkpoint ", source_, ": corrupt payload at byte ", position_, ": ",
             std::forward<Parts>(parts)...);
    }

private:
    std::span<const std::uint8_t> data_;
    std::size_t position_ = 0;
    std::string source_;
};

template <typename Ar, typename T>
requires(std::is_arithmetic_v<T> || std::is_enum_v<T>) void field(Ar& a, T& value) {
    if constexpr (std::is_same_v<T, bool>) {
        if constexpr (Ar::kReading) {
            const std::uint64_t v = a.word(1);
            if (v > 1)
                a.corrupt("a flag is ", v);
            value = v == 1;
        } else {
            a.word(value ? 1 : 0, 1);
        }
    } else if constexpr (std::is_floating_point_v<T>) {
        static_assert(sizeof(T) == 8, "Real is a 64-bit double");
        if constexpr (Ar::kReading)
            value = std::bit_cast<T>(a.word(8));
        else
            a.word(std::bit_cast<std::uint64_t>(value), 8);
    } else if constexpr (std::is_enum_v<T>) {
        using U = std::underlying_type_t<T>;
        U raw = static_cast<U>(value);
        field(a, raw);
        value = static_cast<T>(raw);
    } else {
        using U = std::make_unsigned_t<T>;
        if constexpr (Ar::kReading)
            value = static_cast<T>(static_cast<U>(a.word(sizeof(T))));
        else
            a.word(static_cast<U>(value), sizeof(T));
    }
}

template <typename Ar, typename S, int R, int C, int O, int MR, int MC>
void field(Ar& a, Eigen::Matrix<S, R, C, O, MR, MC>& m) {
    static_assert(R > 0 && C > 0, "fixed-size matrices only");
    for (int i = 0; i < R * C; ++i)
        field(a, m.data()[i]);
}

template <typename Ar>
void field(Ar& a, Quat& q) {
    field(a, q.coeffs());
}

template <typename Ar, typename... T>
void fields(Ar& a, T&... parts) {
    (field(a, parts), ...);
}

template <typename Ar, typename T, std::size_t N>
void field(Ar& a, std::array<T, N>& array) {
    for (T& element : array)
        field(a, element);
}

/// A vector whose elements are written by `each(element)`.
template <typename Ar, typename T, typename Each>
void sequence(Ar& a, std::vector<T>& vector, Each&& each) {
    const std::size_t n = a.count(vector.size());
    if constexpr (Ar::kReading) {
        // Not assign(n, T{}): an Eigen vector's T{} is uninitialised, and copying it is what
        // GCC 12 flags at -O1 (the ASan build). Every element is read just below.
        vector.clear();
        vector.resize(n);
    }
    for (T& element : vector)
        each(element);
}

template <typename Ar, typename T>
void field(Ar& a, std::vector<T>& vector) {
    sequence(a, vector, [&](T& element) { field(a, element); });
}

}  // namespace tumble::checkpoint_io
