#pragma once
// An n x n field on the torus laid out for the fast stencil kernels
// (sim/gray_scott_kernels.hpp, sim/diffusion_kernel.hpp).
//
// Layout: n + 2 rows, each holding a one-cell halo on both sides of the n
// cells; rows start on 64-byte boundaries (the first real cell of a row is
// aligned). The halo holds copies of the wrap edges, so a kernel's inner loop
// over a row is branch-free and contiguous: row -1 copies row n - 1, row n
// copies row 0, column -1 copies column n - 1, column n copies column 0.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <type_traits>

#include "sim/grid.hpp"

namespace sim {

// The cells of a PaddedField, as a kernel's row loop uses them: a pointer
// and a stride, cheap to copy, so a local copy stays in registers across the
// calls of a row loop (the field's own members would be reloaded after each).
template <class Real>
struct PaddedRows {
    Real* origin = nullptr;     // column 0 of row 0
    std::ptrdiff_t stride = 0;  // elements from a row to the next (a multiple of 64 bytes)
    int n = 0;

    // Column 0 of row i, i in -1 .. n (halo rows included); columns -1 and n are the halo.
    Real* row(int i) const { return origin + static_cast<std::ptrdiff_t>(i) * stride; }

    // The halo copies of row i (0 .. n - 1), just written: its two halo
    // columns and, for the first and last rows, the halo row that copies it.
    // It writes only into row i and rows -1 and n, which only rows n - 1 and
    // 0 copy into, so threads may call it for their own rows at once.
    void wrap_row(int i) const {
        Real* cells = row(i);
        cells[-1] = cells[n - 1];
        cells[n] = cells[0];
        if (i == n - 1) std::copy(cells - 1, cells + n + 1, row(-1) - 1);
        if (i == 0) std::copy(cells - 1, cells + n + 1, row(n) - 1);
    }
};

template <class Real>
class PaddedField {
public:
    static constexpr std::size_t kAlign = 64;  // bytes: a cache line, and a whole number of AVX2/AVX-512 vectors

    PaddedField() = default;
    explicit PaddedField(int n) : n_(n) {  // all zero
        const std::ptrdiff_t per_line = static_cast<std::ptrdiff_t>(kAlign / sizeof(Real));
        offset_ = per_line;  // column 0 aligned, the left halo just before it
        stride_ = (offset_ + n + 1 + per_line - 1) / per_line * per_line;
        const std::size_t elements = static_cast<std::size_t>(stride_) * static_cast<std::size_t>(n + 2);
        data_.reset(static_cast<Real*>(::operator new[](elements * sizeof(Real), std::align_val_t(kAlign))));
        std::fill(data_.get(), data_.get() + elements, Real(0));
    }

    int n() const { return n_; }
    PaddedRows<Real> rows() { return {data_.get() + stride_ + offset_, stride_, n_}; }
    PaddedRows<const Real> rows() const { return {data_.get() + stride_ + offset_, stride_, n_}; }

    // Copies g (n x n) in, rounded to Real, halo included.
    void load(const Grid<double>& g) {
        const PaddedRows<Real> cells = rows();
        for (int i = 0; i < n_; ++i) {
            Real* dst = cells.row(i);
            for (int j = 0; j < n_; ++j) dst[j] = static_cast<Real>(g(i, j));
            cells.wrap_row(i);
        }
    }

    template <class T = double>
    Grid<T> extract() const {  // the n x n cells, converted to T
        const PaddedRows<const Real> cells = rows();
        Grid<T> g(n_, n_);
        for (int i = 0; i < n_; ++i) {
            const Real* src = cells.row(i);
            for (int j = 0; j < n_; ++j) g(i, j) = static_cast<T>(src[j]);
        }
        return g;
    }

    // Whether every cell is +0 (all bits clear; -0 does not count).
    bool all_positive_zero() const {
        using Bits = std::conditional_t<sizeof(Real) == 4, std::uint32_t, std::uint64_t>;
        const PaddedRows<const Real> cells = rows();
        Bits any = 0;
        for (int i = 0; i < n_; ++i) {
            const Real* src = cells.row(i);
            for (int j = 0; j < n_; ++j) any |= std::bit_cast<Bits>(src[j]);  // no branch: vectorizes
        }
        return any == 0;
    }

    // Whether every cell has the same bits as `other`'s (the same n).
    bool same_bits(const PaddedField& other) const {
        const PaddedRows<const Real> mine = rows(), theirs = other.rows();
        for (int i = 0; i < n_; ++i)
            if (std::memcmp(mine.row(i), theirs.row(i), static_cast<std::size_t>(n_) * sizeof(Real)) != 0) return false;
        return true;
    }

    // Whether every cell is finite and within `bound` of 0, compared as
    // doubles (as sim::require_finite does; NaN is not within).
    bool within(double bound) const {
        const PaddedRows<const Real> cells = rows();
        bool ok = true;
        for (int i = 0; i < n_; ++i) {
            const Real* src = cells.row(i);
            for (int j = 0; j < n_; ++j) ok &= std::abs(static_cast<double>(src[j])) <= bound;  // no branch
        }
        return ok;
    }

private:
    struct AlignedFree {
        void operator()(Real* p) const { ::operator delete[](p, std::align_val_t(kAlign)); }
    };

    std::unique_ptr<Real[], AlignedFree> data_;
    int n_ = 0;
    std::ptrdiff_t stride_ = 0;  // elements per padded row (multiple of 64 bytes)
    std::ptrdiff_t offset_ = 0;  // column 0 of a row sits at offset_ (aligned); the halo at offset_ - 1 and offset_ + n
};

}  // namespace sim
