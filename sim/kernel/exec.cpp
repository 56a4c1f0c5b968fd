// The operations of a compiled kernel over a chunk of lanes
// (sim/kernel/lanes.hpp), and the masks of its control flow.
//
// Floating-point operations are IEEE's in the kernel's own precision, one
// rounding each (no fused multiply-adds: the sources are built with
// -ffp-contract=off); integers wrap; a conversion from a float to an
// integer saturates (NaN gives 0), as convert_int_sat_rtz does, where
// OpenCL leaves it undefined; a shift's count is taken modulo the width,
// as OpenCL says. An integer division by zero stops the run.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <type_traits>

#include "sim/kernel/ops.hpp"

namespace sim::kernel {

struct Ctx {
    const Compiled* p = nullptr;
    // Lanes of this chunk. A lane loop copies it first (`for (int l = 0,
    // cn = c.n; l < cn; ++l)`): the masks are bytes, a store to one may
    // alias n, and a loop that reads c.n each lane is not vectorised.
    int n = 0;
    std::uint64_t* regs = nullptr;  // registers x lanes
    std::uint8_t* uni = nullptr;    // a flag a register
    std::uint8_t* masks = nullptr;  // mask registers x lanes
    int cur = 1;
    bool any = true, all = true, stop = false;
    const Launch* launch = nullptr;
    long long first = 0;
    Failure* failure = nullptr;
    std::uint32_t trips[lanes];
    long long executed = 0;  // operations run, each over a chunk's lanes (Lanes::executed)
    std::unique_ptr<std::uint64_t[]> reg_storage;
    std::unique_ptr<std::uint8_t[]> uni_storage, mask_storage;
};

namespace {

template <class T>
inline T* reg(Ctx& c, int r) {
    return reinterpret_cast<T*>(c.regs + static_cast<std::size_t>(r) * lanes);
}
inline std::uint8_t* mreg(Ctx& c, int m) { return c.masks + static_cast<std::size_t>(m) * lanes; }

void set_mask(Ctx& c, int m) {
    c.cur = m;
    const std::uint8_t* k = mreg(c, m);
    int count = 0;
    for (int l = 0, cn = c.n; l < cn; ++l) count += k[l];
    c.any = count > 0 && !c.stop;
    c.all = count == c.n;
}

void fail(Ctx& c, int line, int lane, const std::string& what) {
    if (!c.failure->failed) {
        c.failure->failed = true;
        c.failure->item = c.first + lane;
        c.failure->line = line;
        c.failure->what = what;
    }
    c.stop = true;
    c.any = false;
}

void exec(Ctx& c, int block) {
    for (const Op& op : c.p->blocks[static_cast<std::size_t>(block)].ops) {
        if (!c.any) return;
        op.fn(c, op);
        ++c.executed;
    }
}

// A uniform register written out to every lane, before a lane of it is
// written alone.
template <class T>
inline void expand(Ctx& c, int r) {
    if (!c.uni[r]) return;
    T* d = reg<T>(c, r);
    const T v = d[0];
    for (int l = 1, cn = c.n; l < cn; ++l) d[l] = v;
    c.uni[r] = 0;
}

// d = f(a) over the lanes, uniform when a is.
// std::trunc's bits without a call to libm, so that a loop of it
// vectorises: below 2^23 (2^52) a float (double) has a fraction, and the
// integer conversion drops it; the sign is kept for -0. At or above, and
// for infinities and NaN, the value is its own. Exhaustively equal to
// std::trunc over every float, and over 3e8 doubles and their edges.
template <class T>
inline T trunc_exact(T v) {
    using I = std::conditional_t<sizeof(T) == 4, std::int32_t, std::int64_t>;
    const T whole = sizeof(T) == 4 ? T(8388608.0) : T(4503599627370496.0);
    return std::fabs(v) < whole ? std::copysign(T(static_cast<I>(v)), v) : v;
}

template <class D, class A, class F>
inline void map1(Ctx& c, const Op& op, F f) {
    D* d = reg<D>(c, op.dst);
    const A* a = reg<A>(c, op.a);
    if (c.uni[op.a]) {
        d[0] = f(a[0]);
        c.uni[op.dst] = 1;
        return;
    }
    for (int l = 0, cn = c.n; l < cn; ++l) d[l] = f(a[l]);
    c.uni[op.dst] = 0;
}

template <class D, class A, class B, class F>
inline void map2(Ctx& c, const Op& op, F f) {
    D* d = reg<D>(c, op.dst);
    const A* a = reg<A>(c, op.a);
    const B* b = reg<B>(c, op.b);
    const bool ua = c.uni[op.a], ub = c.uni[op.b];
    if (ua && ub) {
        d[0] = f(a[0], b[0]);
        c.uni[op.dst] = 1;
        return;
    }
    const int n = c.n;
    if (ua) {
        const A x = a[0];
        for (int l = 0; l < n; ++l) d[l] = f(x, b[l]);
    } else if (ub) {
        const B y = b[0];
        for (int l = 0; l < n; ++l) d[l] = f(a[l], y);
    } else {
        for (int l = 0; l < n; ++l) d[l] = f(a[l], b[l]);
    }
    c.uni[op.dst] = 0;
}

template <class T, class F>
inline void map3(Ctx& c, const Op& op, F f) {
    T* d = reg<T>(c, op.dst);
    const T* a = reg<T>(c, op.a);
    const T* b = reg<T>(c, op.b);
    const T* e = reg<T>(c, op.c);
    const bool ua = c.uni[op.a], ub = c.uni[op.b], ue = c.uni[op.c];
    if (ua && ub && ue) {
        d[0] = f(a[0], b[0], e[0]);
        c.uni[op.dst] = 1;
        return;
    }
    for (int l = 0, cn = c.n; l < cn; ++l) d[l] = f(a[ua ? 0 : l], b[ub ? 0 : l], e[ue ? 0 : l]);
    c.uni[op.dst] = 0;
}

template <class T>
T from_op(const Op& op) {
    if constexpr (std::is_floating_point_v<T>) return static_cast<T>(op.f);
    else return static_cast<T>(static_cast<std::uint64_t>(op.i));
}

template <class T>
void op_constant(Ctx& c, const Op& op) {
    reg<T>(c, op.dst)[0] = from_op<T>(op);
    c.uni[op.dst] = 1;
}

// A float to an integer: toward zero, saturated, NaN to 0.
template <class To, class From>
inline To saturate(From v) {
    if constexpr (std::is_floating_point_v<From> && std::is_integral_v<To>) {
        if (std::isnan(v)) return 0;
        if (v <= static_cast<From>(std::numeric_limits<To>::min())) return std::numeric_limits<To>::min();
        if (v >= static_cast<From>(std::numeric_limits<To>::max())) return std::numeric_limits<To>::max();
        return static_cast<To>(v);
    } else {
        return static_cast<To>(v);
    }
}

template <class From, class To, bool Bool>
void op_convert(Ctx& c, const Op& op) {
    if constexpr (Bool) map1<To, From>(c, op, [](From v) { return static_cast<To>(v != From(0)); });
    else map1<To, From>(c, op, [](From v) { return saturate<To>(v); });
}

template <class T>
void op_copy(Ctx& c, const Op& op) {
    T* d = reg<T>(c, op.dst);
    const T* a = reg<T>(c, op.a);
    if (c.uni[op.a]) {
        d[0] = a[0];
        c.uni[op.dst] = 1;
    } else {
        if (d != a) std::memcpy(d, a, sizeof(T) * static_cast<std::size_t>(c.n));
        c.uni[op.dst] = 0;
    }
}

template <class T>
void op_assign(Ctx& c, const Op& op) {
    if (c.all) return op_copy<T>(c, op);
    T* d = reg<T>(c, op.dst);
    const T* a = reg<T>(c, op.a);
    if (c.uni[op.dst] && c.uni[op.a] && std::memcmp(d, a, sizeof(T)) == 0) return;
    expand<T>(c, op.dst);
    const std::uint8_t* m = mreg(c, c.cur);
    if (c.uni[op.a]) {
        const T v = a[0];
        for (int l = 0, cn = c.n; l < cn; ++l) d[l] = m[l] ? v : d[l];
    } else {
        for (int l = 0, cn = c.n; l < cn; ++l) d[l] = m[l] ? a[l] : d[l];
    }
}

template <class T>
using wrap_t = std::make_unsigned_t<T>;

template <class T, ops::Unary U, class R>
void op_unary(Ctx& c, const Op& op) {
    if constexpr (U == ops::Unary::neg) {
        if constexpr (std::is_floating_point_v<T>) map1<T, T>(c, op, [](T v) { return -v; });
        else map1<T, T>(c, op, [](T v) { return static_cast<T>(wrap_t<T>(0) - static_cast<wrap_t<T>>(v)); });
    } else if constexpr (U == ops::Unary::bit_not) {
        if constexpr (std::is_integral_v<T>) map1<T, T>(c, op, [](T v) { return static_cast<T>(~v); });
    } else if constexpr (U == ops::Unary::log_not) {
        map1<R, T>(c, op, [](T v) { return static_cast<R>(v == T(0)); });
    } else {
        map1<R, T>(c, op, [](T v) { return static_cast<R>(v == T(0) ? -1 : 0); });
    }
}

template <class T, ops::Binary B>
void op_binary(Ctx& c, const Op& op) {
    using ops::Binary;
    if constexpr (std::is_floating_point_v<T>) {
        if constexpr (B == Binary::add) map2<T, T, T>(c, op, [](T x, T y) { return x + y; });
        else if constexpr (B == Binary::sub) map2<T, T, T>(c, op, [](T x, T y) { return x - y; });
        else if constexpr (B == Binary::mul) map2<T, T, T>(c, op, [](T x, T y) { return x * y; });
        else if constexpr (B == Binary::div) map2<T, T, T>(c, op, [](T x, T y) { return x / y; });
    } else {
        using U = wrap_t<T>;
        constexpr int bits = sizeof(T) * 8;
        if constexpr (B == Binary::add) map2<T, T, T>(c, op, [](T x, T y) { return static_cast<T>(U(x) + U(y)); });
        else if constexpr (B == Binary::sub) map2<T, T, T>(c, op, [](T x, T y) { return static_cast<T>(U(x) - U(y)); });
        else if constexpr (B == Binary::mul) map2<T, T, T>(c, op, [](T x, T y) { return static_cast<T>(U(x) * U(y)); });
        else if constexpr (B == Binary::bit_and) map2<T, T, T>(c, op, [](T x, T y) { return static_cast<T>(x & y); });
        else if constexpr (B == Binary::bit_or) map2<T, T, T>(c, op, [](T x, T y) { return static_cast<T>(x | y); });
        else if constexpr (B == Binary::bit_xor) map2<T, T, T>(c, op, [](T x, T y) { return static_cast<T>(x ^ y); });
        else if constexpr (B == Binary::shl)
            map2<T, T, T>(c, op, [](T x, T y) { return static_cast<T>(U(x) << (U(y) & U(bits - 1))); });
        else if constexpr (B == Binary::shr)
            map2<T, T, T>(c, op, [](T x, T y) { return static_cast<T>(x >> (U(y) & U(bits - 1))); });
        else {
            // a division: no lane of the mask divides by zero
            const T* b = reg<T>(c, op.b);
            const std::uint8_t* m = mreg(c, c.cur);
            for (int l = 0; l < (c.uni[op.b] ? 1 : c.n); ++l)
                if (b[l] == 0 && (c.uni[op.b] ? c.any : m[l] != 0)) {
                    int lane = l;
                    if (c.uni[op.b])
                        for (lane = 0; lane < c.n && !m[lane]; ++lane) {}
                    return fail(c, op.line, lane, "an integer division by zero");
                }
            // lanes outside the mask may divide by zero: they give 0
            auto safe = [](T x, T y) -> T {
                if (y == 0) return 0;
                if constexpr (std::is_signed_v<T>)
                    if (y == T(-1)) return B == Binary::div ? static_cast<T>(U(0) - U(x)) : T(0);
                return B == Binary::div ? static_cast<T>(x / y) : static_cast<T>(x % y);
            };
            map2<T, T, T>(c, op, safe);
        }
    }
}

template <class T, ops::Compare K, class R, bool Vec>
void op_compare(Ctx& c, const Op& op) {
    constexpr R yes = Vec ? R(-1) : R(1);
    using ops::Compare;
    if constexpr (K == Compare::eq) map2<R, T, T>(c, op, [](T x, T y) { return x == y ? yes : R(0); });
    else if constexpr (K == Compare::ne) map2<R, T, T>(c, op, [](T x, T y) { return x != y ? yes : R(0); });
    else if constexpr (K == Compare::lt) map2<R, T, T>(c, op, [](T x, T y) { return x < y ? yes : R(0); });
    else if constexpr (K == Compare::gt) map2<R, T, T>(c, op, [](T x, T y) { return x > y ? yes : R(0); });
    else if constexpr (K == Compare::le) map2<R, T, T>(c, op, [](T x, T y) { return x <= y ? yes : R(0); });
    else map2<R, T, T>(c, op, [](T x, T y) { return x >= y ? yes : R(0); });
}

template <class T>
T sign_of(T x) {
    if (std::isnan(x)) return 0;
    if (x > 0) return 1;
    if (x < 0) return -1;
    return x;  // keeps the zero's sign
}

template <class T, ops::Math1 M, bool Vec>
void op_math1(Ctx& c, const Op& op) {
    using ops::Math1;
    if constexpr (M == Math1::iabs) {
        map1<T, T>(c, op, [](T v) {
            using U = wrap_t<T>;
            return static_cast<T>(v < 0 ? U(0) - U(v) : U(v));
        });
    } else if constexpr (M == Math1::isnan || M == Math1::isinf || M == Math1::isfinite) {
        using R = std::conditional_t<sizeof(T) == 8, std::int64_t, std::int32_t>;
        constexpr R yes = Vec ? R(-1) : R(1);
        map1<R, T>(c, op, [](T v) {
            bool r;
            if constexpr (M == Math1::isnan) r = std::isnan(v);
            else if constexpr (M == Math1::isinf) r = std::isinf(v);
            else r = std::isfinite(v);
            return r ? yes : R(0);
        });
    } else {
        map1<T, T>(c, op, [](T v) -> T {
            if constexpr (M == Math1::sqrt) return std::sqrt(v);
            else if constexpr (M == Math1::rsqrt) return T(1) / std::sqrt(v);
            else if constexpr (M == Math1::cbrt) return std::cbrt(v);
            else if constexpr (M == Math1::exp) return std::exp(v);
            else if constexpr (M == Math1::exp2) return std::exp2(v);
            else if constexpr (M == Math1::exp10) return std::pow(T(10), v);
            else if constexpr (M == Math1::expm1) return std::expm1(v);
            else if constexpr (M == Math1::log) return std::log(v);
            else if constexpr (M == Math1::log2) return std::log2(v);
            else if constexpr (M == Math1::log10) return std::log10(v);
            else if constexpr (M == Math1::log1p) return std::log1p(v);
            else if constexpr (M == Math1::sin) return std::sin(v);
            else if constexpr (M == Math1::cos) return std::cos(v);
            else if constexpr (M == Math1::tan) return std::tan(v);
            else if constexpr (M == Math1::asin) return std::asin(v);
            else if constexpr (M == Math1::acos) return std::acos(v);
            else if constexpr (M == Math1::atan) return std::atan(v);
            else if constexpr (M == Math1::sinh) return std::sinh(v);
            else if constexpr (M == Math1::cosh) return std::cosh(v);
            else if constexpr (M == Math1::tanh) return std::tanh(v);
            else if constexpr (M == Math1::asinh) return std::asinh(v);
            else if constexpr (M == Math1::acosh) return std::acosh(v);
            else if constexpr (M == Math1::atanh) return std::atanh(v);
            else if constexpr (M == Math1::fabs) return std::fabs(v);
            else if constexpr (M == Math1::floor) return std::floor(v);
            else if constexpr (M == Math1::ceil) return std::ceil(v);
            else if constexpr (M == Math1::round) {
                // half away from zero, as std::round, without a call to libm:
                // v - trunc(v) is exact (the same bits as std::round for every float)
                const T r = trunc_exact(v);
                return std::fabs(v - r) >= T(0.5) ? r + std::copysign(T(1), v) : r;
            }
            else if constexpr (M == Math1::trunc) return trunc_exact(v);
            else if constexpr (M == Math1::rint) return std::nearbyint(v);
            else if constexpr (M == Math1::sign) return sign_of(v);
            else if constexpr (M == Math1::erf) return std::erf(v);
            else if constexpr (M == Math1::erfc) return std::erfc(v);
            else if constexpr (M == Math1::tgamma) return std::tgamma(v);
            else return std::lgamma(v);
        });
    }
}

template <class T, ops::Math2 M, bool Vec>
void op_math2(Ctx& c, const Op& op) {
    using ops::Math2;
    if constexpr (M >= Math2::isless) {
        using R = std::conditional_t<sizeof(T) == 8, std::int64_t, std::int32_t>;
        constexpr R yes = Vec ? R(-1) : R(1);
        map2<R, T, T>(c, op, [](T x, T y) {
            bool r;
            if constexpr (M == Math2::isless) r = std::isless(x, y);
            else if constexpr (M == Math2::isgreater) r = std::isgreater(x, y);
            else if constexpr (M == Math2::islessequal) r = std::islessequal(x, y);
            else if constexpr (M == Math2::isgreaterequal) r = std::isgreaterequal(x, y);
            else if constexpr (M == Math2::isequal) r = x == y;
            else r = x != y;
            return r ? yes : R(0);
        });
    } else {
        map2<T, T, T>(c, op, [](T x, T y) -> T {
            // min and max as OpenCL defines them: y < x ? y : x, x < y ? y : x
            if constexpr (M == Math2::min) return y < x ? y : x;
            else if constexpr (M == Math2::max) return x < y ? y : x;
            else if constexpr (!std::is_floating_point_v<T>) return x;  // no other on integers
            else if constexpr (M == Math2::pow || M == Math2::powr) return std::pow(x, y);
            else if constexpr (M == Math2::atan2) return std::atan2(x, y);
            else if constexpr (M == Math2::hypot) return std::hypot(x, y);
            else if constexpr (M == Math2::fmod) return std::fmod(x, y);
            else if constexpr (M == Math2::fmin) return std::fmin(x, y);
            else if constexpr (M == Math2::fmax) return std::fmax(x, y);
            else if constexpr (M == Math2::step) return y < x ? T(0) : T(1);
            else if constexpr (M == Math2::copysign) return std::copysign(x, y);
            else if constexpr (M == Math2::fdim) return std::fdim(x, y);
            else return std::remainder(x, y);
        });
    }
}

// d = fma(a, b, e) over n lanes. fma rounds once whether the CPU has the
// instruction or libm computes it, so the clone with it (chosen once at
// load time) gives the same bits; without it each lane is a libm call.
template <class T>
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("fma", "default")))
#endif
[[gnu::noinline]] void fma_lanes(T* __restrict d, const T* __restrict a, const T* __restrict b, const T* __restrict e,
                                 int n) {
#ifdef _OPENMP
#pragma omp simd
#endif
    for (int l = 0; l < n; ++l) d[l] = std::fma(a[l], b[l], e[l]);
}

template <class T>
void op_fma(Ctx& c, const Op& op) {
    const bool ua = c.uni[op.a], ub = c.uni[op.b], ue = c.uni[op.c];
    T* d = reg<T>(c, op.dst);
    const T* a = reg<T>(c, op.a);
    const T* b = reg<T>(c, op.b);
    const T* e = reg<T>(c, op.c);
    if (ua && ub && ue) {
        d[0] = std::fma(a[0], b[0], e[0]);
        c.uni[op.dst] = 1;
        return;
    }
    // a uniform operand spread to every lane first (d may be one of them)
    alignas(64) T spread[3][lanes];
    const auto lanes_of = [&](const T* x, bool u, int k) -> const T* {
        if (!u) return x;
        std::fill(spread[k], spread[k] + c.n, x[0]);
        return spread[k];
    };
    const T* xa = lanes_of(a, ua, 0);
    const T* xb = lanes_of(b, ub, 1);
    const T* xe = lanes_of(e, ue, 2);
    if (d == xa || d == xb || d == xe) {
        alignas(64) T out[lanes];
        fma_lanes<T>(out, xa, xb, xe, c.n);
        std::memcpy(d, out, sizeof(T) * static_cast<std::size_t>(c.n));
    } else {
        fma_lanes<T>(d, xa, xb, xe, c.n);
    }
    c.uni[op.dst] = 0;
}

template <class T, ops::Math3 M>
void op_math3(Ctx& c, const Op& op) {
    using ops::Math3;
    if constexpr (M == Math3::fma && std::is_floating_point_v<T>) return op_fma<T>(c, op);
    map3<T>(c, op, [](T x, T y, T z) -> T {
        if constexpr (M == Math3::clamp) {
            if constexpr (std::is_floating_point_v<T>) return std::fmin(std::fmax(x, y), z);
            else return x < y ? y : (z < x ? z : x);
        } else if constexpr (M == Math3::mix) {
            return x + (y - x) * z;
        } else if constexpr (M == Math3::fma) {
            return std::fma(x, y, z);
        } else if constexpr (M == Math3::mad) {
            return x * y + z;
        } else {
            const T t = std::fmin(std::fmax((z - x) / (y - x), T(0)), T(1));
            return t * t * (T(3) - T(2) * t);
        }
    });
}

template <class T>
void op_select(Ctx& c, const Op& op) {
    T* d = reg<T>(c, op.dst);
    const T* a = reg<T>(c, op.a);
    const T* b = reg<T>(c, op.b);
    const std::uint8_t* m = mreg(c, op.c);
    const bool ua = c.uni[op.a], ub = c.uni[op.b];
    bool all = true, none = true;
    for (int l = 0, cn = c.n; l < cn; ++l) (m[l] ? none : all) = false;
    if ((all && ub) || (none && ua)) {
        d[0] = all ? b[0] : a[0];
        c.uni[op.dst] = 1;
        return;
    }
    for (int l = 0, cn = c.n; l < cn; ++l) d[l] = m[l] ? b[ub ? 0 : l] : a[ua ? 0 : l];
    c.uni[op.dst] = 0;
}

template <class T>
void op_to_mask(Ctx& c, const Op& op) {
    std::uint8_t* d = mreg(c, op.dst);
    const T* a = reg<T>(c, op.a);
    if (c.uni[op.a]) std::memset(d, a[0] != T(0), static_cast<std::size_t>(c.n));
    else
        for (int l = 0, cn = c.n; l < cn; ++l) d[l] = a[l] != T(0);
}

template <class T>
void op_sign_mask(Ctx& c, const Op& op) {
    std::uint8_t* d = mreg(c, op.dst);
    const T* a = reg<T>(c, op.a);
    for (int l = 0, cn = c.n; l < cn; ++l) d[l] = a[c.uni[op.a] ? 0 : l] < T(0);
}

void op_from_mask(Ctx& c, const Op& op) {
    std::int32_t* d = reg<std::int32_t>(c, op.dst);
    const std::uint8_t* a = mreg(c, op.a);
    for (int l = 0, cn = c.n; l < cn; ++l) d[l] = a[l];
    c.uni[op.dst] = 0;
}

void op_mask_and(Ctx& c, const Op& op) {
    std::uint8_t* d = mreg(c, op.dst);
    const std::uint8_t *a = mreg(c, op.a), *b = mreg(c, op.b);
    for (int l = 0, cn = c.n; l < cn; ++l) d[l] = a[l] & b[l];
}
void op_mask_or(Ctx& c, const Op& op) {
    std::uint8_t* d = mreg(c, op.dst);
    const std::uint8_t *a = mreg(c, op.a), *b = mreg(c, op.b);
    for (int l = 0, cn = c.n; l < cn; ++l) d[l] = a[l] | b[l];
}
void op_mask_not(Ctx& c, const Op& op) {
    std::uint8_t* d = mreg(c, op.dst);
    const std::uint8_t* a = mreg(c, op.a);
    for (int l = 0, cn = c.n; l < cn; ++l) d[l] = a[l] ^ 1;
}

// Whether a lane of the mask (n lanes) has an index at or past ubound (a
// negative one, as unsigned, is past it). The compare of 64-bit lanes
// vectorises from SSE4.2 on, past the build's SSE2 baseline: the clone
// for the CPU is chosen once at load time; the answer is the same.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
[[gnu::noinline]] bool any_past(const std::uint8_t* __restrict m, const std::int64_t* __restrict idx, int n,
                                std::uint64_t ubound) {
    std::uint8_t any = 0;
    for (int l = 0; l < n; ++l) any |= m[l] & static_cast<std::uint8_t>(static_cast<std::uint64_t>(idx[l]) >= ubound);
    return any != 0;
}

// The first lane of the mask whose index is outside [0, bound), or -1.
int outside(Ctx& c, const std::int64_t* idx, bool uniform, long long bound) {
    const std::uint8_t* m = mreg(c, c.cur);
    if (uniform) {
        if (idx[0] >= 0 && idx[0] < bound) return -1;
        for (int l = 0, cn = c.n; l < cn; ++l)
            if (m[l]) return l;
        return -1;
    }
    if (!any_past(m, idx, c.n, static_cast<std::uint64_t>(bound))) return -1;
    for (int l = 0, cn = c.n; l < cn; ++l)
        if (m[l] && (idx[l] < 0 || idx[l] >= bound)) return l;
    return -1;
}

void op_check_index(Ctx& c, const Op& op) {
    const std::int64_t* idx = reg<std::int64_t>(c, op.a);
    const int bad = outside(c, idx, c.uni[op.a], op.i);
    if (bad >= 0)
        fail(c, op.line, bad,
             "index " + std::to_string(idx[c.uni[op.a] ? 0 : bad]) + " of " + c.p->arrays[static_cast<std::size_t>(op.aux)].name +
                 " is outside 0 to " + std::to_string(op.i - 1));
}

std::string buffer_message(const BufferView& v, std::int64_t index, long long elements) {
    return "index " + std::to_string(index) + " of " + v.name + " is outside 0 to " + std::to_string(elements - 1);
}

template <class T>
void op_buffer_load(Ctx& c, const Op& op) {
    const auto view = static_cast<std::size_t>(op.aux);
    const BufferView& v = c.p->buffers[view];
    const long long elements = c.launch->elements[view];
    const std::int64_t* idx = reg<std::int64_t>(c, op.a);
    const bool u = c.uni[op.a];
    const bool checked = op.c == 1;  // another component of this element was loaded just before, and checked
    if (!checked) {
        const int bad = outside(c, idx, u, elements);
        if (bad >= 0) return fail(c, op.line, bad, buffer_message(v, idx[u ? 0 : bad], elements));
    }
    const T* data = static_cast<const T*>(v.output ? c.launch->out[view] : c.launch->data[view]);
    const int w = v.width;
    const std::uint8_t* m = mreg(c, c.cur);
    if (v.output && !checked) {
        // an output is read where this work item wrote it, else what it
        // reads is another's, or undefined
        const std::int32_t* stamp = c.launch->stamps[view];
        for (int l = 0, cn = c.n; l < cn; ++l) {
            if (!m[l]) continue;
            const std::int64_t i = idx[u ? 0 : l];
            const std::int32_t who = std::atomic_ref<const std::int32_t>(stamp[i]).load(std::memory_order_relaxed);
            if (who != static_cast<std::int32_t>(c.first + l))
                return fail(c, op.line, l,
                            "reads " + v.name + "[" + std::to_string(i) +
                                "], an output this work item has not written in this step");
        }
    }
    T* d = reg<T>(c, op.dst);
    if (u) {
        d[0] = data[idx[0] * w + op.i];
        c.uni[op.dst] = 1;
        return;
    }
    if (c.all) {
        for (int l = 0, cn = c.n; l < cn; ++l) d[l] = data[idx[l] * w + op.i];
    } else {
        for (int l = 0, cn = c.n; l < cn; ++l) d[l] = m[l] ? data[idx[l] * w + op.i] : T(0);
    }
    c.uni[op.dst] = 0;
}

template <class T>
void op_buffer_store(Ctx& c, const Op& op) {
    const auto view = static_cast<std::size_t>(op.aux);
    const BufferView& v = c.p->buffers[view];
    const long long elements = c.launch->elements[view];
    const std::int64_t* idx = reg<std::int64_t>(c, op.a);
    const bool u = c.uni[op.a];
    const int bad = outside(c, idx, u, elements);
    if (bad >= 0) return fail(c, op.line, bad, buffer_message(v, idx[u ? 0 : bad], elements));
    T* data = static_cast<T*>(c.launch->out[view]);
    std::int32_t* stamp = c.launch->stamps[view];
    const T* b = reg<T>(c, op.b);
    const bool ub = c.uni[op.b];
    const std::uint8_t* m = mreg(c, c.cur);
    const int w = v.width;
    for (int l = 0, cn = c.n; l < cn; ++l) {
        if (!m[l]) continue;
        const std::int64_t i = idx[u ? 0 : l];
        const auto me = static_cast<std::int32_t>(c.first + l);
        const std::int32_t was = std::atomic_ref<std::int32_t>(stamp[i]).exchange(me, std::memory_order_relaxed);
        if (was != -1 && was != me)
            return fail(c, op.line, l,
                        "writes " + v.name + "[" + std::to_string(i) + "], which work item " + std::to_string(was) +
                            " wrote in this step too");
        data[i * w + op.i] = b[ub ? 0 : l];
    }
}

template <class T>
void op_array_load(Ctx& c, const Op& op) {
    const ArrayInfo& a = c.p->arrays[static_cast<std::size_t>(op.aux)];
    const std::int64_t* idx = reg<std::int64_t>(c, op.a);
    T* d = reg<T>(c, op.dst);
    if (c.uni[op.a]) {
        const int r = a.base + static_cast<int>(idx[0]) * a.width + static_cast<int>(op.i);
        // the index was checked in the mask's lanes; elsewhere it may be anything
        if (idx[0] < 0 || idx[0] >= a.count) {
            d[0] = 0;
            c.uni[op.dst] = 1;
            return;
        }
        const T* s = reg<T>(c, r);
        if (c.uni[r]) {
            d[0] = s[0];
            c.uni[op.dst] = 1;
        } else {
            std::memcpy(d, s, sizeof(T) * static_cast<std::size_t>(c.n));
            c.uni[op.dst] = 0;
        }
        return;
    }
    for (int l = 0, cn = c.n; l < cn; ++l) {
        const std::int64_t i = idx[l];
        if (i < 0 || i >= a.count) {
            d[l] = 0;
            continue;
        }
        const int r = a.base + static_cast<int>(i) * a.width + static_cast<int>(op.i);
        d[l] = reg<T>(c, r)[c.uni[r] ? 0 : l];
    }
    c.uni[op.dst] = 0;
}

template <class T>
void op_array_store(Ctx& c, const Op& op) {
    const ArrayInfo& a = c.p->arrays[static_cast<std::size_t>(op.aux)];
    const std::int64_t* idx = reg<std::int64_t>(c, op.a);
    const T* b = reg<T>(c, op.b);
    const bool ub = c.uni[op.b];
    if (c.uni[op.a]) {
        // one element for every lane: an assignment
        Op as;
        as.dst = a.base + static_cast<int>(idx[0]) * a.width + static_cast<int>(op.i);
        as.a = op.b;
        return op_assign<T>(c, as);
    }
    const std::uint8_t* m = mreg(c, c.cur);
    for (int l = 0, cn = c.n; l < cn; ++l) {
        if (!m[l]) continue;
        const int r = a.base + static_cast<int>(idx[l]) * a.width + static_cast<int>(op.i);
        expand<T>(c, r);
        reg<T>(c, r)[l] = b[ub ? 0 : l];
    }
}

void op_global_size(Ctx& c, const Op& op) {
    reg<std::uint64_t>(c, op.dst)[0] = static_cast<std::uint64_t>(c.p->global[op.i]);
    c.uni[op.dst] = 1;
}

void copy_mask(Ctx& c, int to, int from) {
    if (to != from) std::memcpy(mreg(c, to), mreg(c, from), static_cast<std::size_t>(c.n));
}

void op_if(Ctx& c, const Op& op) {
    const IfNode& f = c.p->ifs[static_cast<std::size_t>(op.aux)];
    const std::uint8_t* m = mreg(c, c.cur);
    const std::uint8_t* k = mreg(c, f.cond);
    std::uint8_t* t = mreg(c, f.then_mask);
    std::uint8_t* e = mreg(c, f.else_mask);
    int nt = 0, ne = 0;
    for (int l = 0, cn = c.n; l < cn; ++l) {
        t[l] = m[l] & k[l];
        e[l] = m[l] & (k[l] ^ 1);
        nt += t[l];
        ne += e[l];
    }
    if (ne == 0) {  // every lane the same way: no join
        exec(c, f.then_block);
        return;
    }
    if (nt == 0) {
        if (f.else_block >= 0) exec(c, f.else_block);
        return;
    }
    std::uint8_t* j = mreg(c, f.join);
    set_mask(c, f.then_mask);
    exec(c, f.then_block);
    if (c.stop) return;
    copy_mask(c, f.join, c.cur);
    if (f.else_block >= 0) {
        set_mask(c, f.else_mask);
        exec(c, f.else_block);
        if (c.stop) return;
    }
    const std::uint8_t* after = mreg(c, f.else_block >= 0 ? c.cur : f.else_mask);
    for (int l = 0, cn = c.n; l < cn; ++l) j[l] |= after[l];
    set_mask(c, f.join);
}

void op_loop(Ctx& c, const Op& op) {
    const LoopNode& L = c.p->loops[static_cast<std::size_t>(op.aux)];
    std::uint8_t* lm = mreg(c, L.lm);
    std::uint8_t* ex = mreg(c, L.exit);
    std::memset(mreg(c, L.broken), 0, lanes);
    std::memset(ex, 0, lanes);
    copy_mask(c, L.lm, c.cur);
    const long long budget = c.p->trip_budget;
    bool first = true;
    for (;;) {
        set_mask(c, L.lm);
        if (!c.any) break;
        if (L.test_first || !first) {
            if (L.cond_block >= 0) exec(c, L.cond_block);
            if (c.stop) return;
            if (L.cond >= 0) {
                const std::uint8_t* k = mreg(c, L.cond);
                int count = 0;
                for (int l = 0, cn = c.n; l < cn; ++l) {
                    ex[l] |= lm[l] & (k[l] ^ 1);
                    lm[l] &= k[l];
                    count += lm[l];
                }
                if (count == 0) break;
                set_mask(c, L.lm);
            }
        }
        first = false;
        for (int l = 0, cn = c.n; l < cn; ++l) {
            c.trips[l] += lm[l];
            if (c.trips[l] > budget)
                return fail(c, op.line, l,
                            "a work item took more than " + std::to_string(budget) + " loop iterations in one step");
        }
        std::memset(mreg(c, L.continued), 0, lanes);
        exec(c, L.body);
        if (c.stop) return;
        const std::uint8_t* after = mreg(c, c.cur);
        const std::uint8_t* cont = mreg(c, L.continued);
        for (int l = 0, cn = c.n; l < cn; ++l) lm[l] = after[l] | cont[l];
        if (L.step >= 0) {
            set_mask(c, L.lm);
            if (c.any) exec(c, L.step);
            if (c.stop) return;
            copy_mask(c, L.lm, c.cur);
        }
    }
    const std::uint8_t* br = mreg(c, L.broken);
    for (int l = 0, cn = c.n; l < cn; ++l) ex[l] |= br[l];
    set_mask(c, L.exit);
}

void op_switch(Ctx& c, const Op& op) {
    const SwitchNode& s = c.p->switches[static_cast<std::size_t>(op.aux)];
    copy_mask(c, s.entry, c.cur);
    const std::uint8_t* entry = mreg(c, s.entry);
    std::uint8_t* fall = mreg(c, s.fall);
    std::uint8_t* enter = mreg(c, s.enter);
    std::memset(fall, 0, lanes);
    std::memset(mreg(c, s.broken), 0, lanes);
    const std::int64_t* sel = reg<std::int64_t>(c, s.selector);
    const bool u = c.uni[s.selector];
    // Whether a value is among any segment's labels (a default takes the others).
    const auto labelled = [&s](std::int64_t v) {
        for (const SwitchNode::Segment& seg : s.segments)
            for (std::int64_t label : seg.labels)
                if (label == v) return true;
        return false;
    };
    const auto hits = [&labelled](const SwitchNode::Segment& seg, std::int64_t v) {
        for (std::int64_t label : seg.labels)
            if (label == v) return true;
        return seg.is_default && !labelled(v);
    };
    bool falling = false;  // some lane falls through into the next segment
    for (const SwitchNode::Segment& seg : s.segments) {
        if (u) {
            const bool hit = hits(seg, sel[0]);
            if (!hit && !falling) continue;  // no lane enters it
            if (hit)
                for (int l = 0, cn = c.n; l < cn; ++l) enter[l] = static_cast<std::uint8_t>(fall[l] | entry[l]);
            else
                std::memcpy(enter, fall, lanes);
        } else {
            for (int l = 0, cn = c.n; l < cn; ++l)
                enter[l] = static_cast<std::uint8_t>(fall[l] | (entry[l] & hits(seg, sel[l])));
        }
        set_mask(c, s.enter);
        if (c.any) exec(c, seg.block);
        if (c.stop) return;
        copy_mask(c, s.fall, c.cur);
        falling = false;
        for (int l = 0, cn = c.n; l < cn; ++l) falling = falling || fall[l];
    }
    // after it: the lanes that broke out, fell off its end, or matched no
    // label (without a default, a switch passes those by)
    const std::uint8_t* br = mreg(c, s.broken);
    bool has_default = false;
    for (const SwitchNode::Segment& seg : s.segments) has_default = has_default || seg.is_default;
    const bool uniform_hit = u && (has_default || labelled(sel[0]));
    for (int l = 0, cn = c.n; l < cn; ++l) {
        const bool hit = u ? uniform_hit : has_default || labelled(sel[l]);
        fall[l] |= br[l] | (entry[l] & !hit);
    }
    set_mask(c, s.fall);
}

void op_guard(Ctx& c, const Op& op) {
    const GuardNode& g = c.p->guards[static_cast<std::size_t>(op.aux)];
    copy_mask(c, g.saved, c.cur);
    const std::uint8_t* m = mreg(c, g.saved);
    const std::uint8_t* k = mreg(c, g.cond);
    std::uint8_t* f = mreg(c, g.first_mask);
    std::uint8_t* s = mreg(c, g.second_mask);
    for (int l = 0, cn = c.n; l < cn; ++l) {
        f[l] = m[l] & k[l];
        s[l] = m[l] & (k[l] ^ 1);
    }
    if (g.first >= 0) {
        set_mask(c, g.first_mask);
        if (c.any) exec(c, g.first);
        if (c.stop) return;
    }
    if (g.second >= 0) {
        set_mask(c, g.second_mask);
        if (c.any) exec(c, g.second);
        if (c.stop) return;
    }
    set_mask(c, g.saved);
}

void op_jump(Ctx& c, const Op& op) {
    std::uint8_t* d = mreg(c, op.aux);
    const std::uint8_t* m = mreg(c, c.cur);
    for (int l = 0, cn = c.n; l < cn; ++l) d[l] |= m[l];
    c.cur = 0;
    c.any = false;
    c.all = false;
}

void op_call(Ctx& c, const Op& op) {
    const CallNode& k = c.p->calls[static_cast<std::size_t>(op.aux)];
    std::memset(mreg(c, k.returned), 0, lanes);
    exec(c, k.body);
    if (c.stop) return;
    std::uint8_t* d = mreg(c, k.join);
    const std::uint8_t *m = mreg(c, c.cur), *r = mreg(c, k.returned);
    for (int l = 0, cn = c.n; l < cn; ++l) d[l] = m[l] | r[l];
    set_mask(c, k.join);
}

// The C++ type of each scalar, for the tables below.
#define FIGGEN_BY_TYPE(s, F)                     \
    switch (s) {                                 \
    case Scalar::b:                              \
    case Scalar::i32: return F(std::int32_t);    \
    case Scalar::u32: return F(std::uint32_t);   \
    case Scalar::i64: return F(std::int64_t);    \
    case Scalar::u64: return F(std::uint64_t);   \
    case Scalar::f32: return F(float);           \
    case Scalar::f64: return F(double);          \
    }                                            \
    return nullptr

template <class From>
OpFn convert_from(Scalar to) {
#define F(T) &op_convert<From, T, false>
    if (to == Scalar::b) return &op_convert<From, std::int32_t, true>;
    FIGGEN_BY_TYPE(to, F);
#undef F
}

}  // namespace

namespace ops {

OpFn constant(Scalar s) {
#define F(T) &op_constant<T>
    FIGGEN_BY_TYPE(s, F);
#undef F
}
OpFn convert(Scalar from, Scalar to) {
#define F(T) convert_from<T>(to)
    FIGGEN_BY_TYPE(from, F);
#undef F
}
OpFn convert_sat(Scalar from, Scalar to) { return convert(from, to); }
OpFn copy(Scalar s) {
#define F(T) &op_copy<T>
    FIGGEN_BY_TYPE(s, F);
#undef F
}
OpFn assign(Scalar s) {
#define F(T) &op_assign<T>
    FIGGEN_BY_TYPE(s, F);
#undef F
}

template <Unary U>
OpFn unary_of(Scalar s, Scalar result) {
    const bool wide = bytes_of(result) == 8;
    if constexpr (U == Unary::log_not || U == Unary::vec_not) {
#define F(T) wide ? &op_unary<T, U, std::int64_t> : &op_unary<T, U, std::int32_t>
        FIGGEN_BY_TYPE(s, F);
#undef F
    } else {
#define F(T) &op_unary<T, U, T>
        FIGGEN_BY_TYPE(s, F);
#undef F
    }
}
OpFn unary(Unary u, Scalar s, Scalar result) {
    switch (u) {
    case Unary::neg: return unary_of<Unary::neg>(s, result);
    case Unary::bit_not: return unary_of<Unary::bit_not>(s, result);
    case Unary::log_not: return unary_of<Unary::log_not>(s, result);
    case Unary::vec_not: return unary_of<Unary::vec_not>(s, result);
    }
    return nullptr;
}

template <Binary B>
OpFn binary_of(Scalar s) {
#define F(T) &op_binary<T, B>
    FIGGEN_BY_TYPE(s, F);
#undef F
}
OpFn binary(Binary b, Scalar s) {
    switch (b) {
    case Binary::add: return binary_of<Binary::add>(s);
    case Binary::sub: return binary_of<Binary::sub>(s);
    case Binary::mul: return binary_of<Binary::mul>(s);
    case Binary::div: return binary_of<Binary::div>(s);
    case Binary::rem: return binary_of<Binary::rem>(s);
    case Binary::bit_and: return binary_of<Binary::bit_and>(s);
    case Binary::bit_or: return binary_of<Binary::bit_or>(s);
    case Binary::bit_xor: return binary_of<Binary::bit_xor>(s);
    case Binary::shl: return binary_of<Binary::shl>(s);
    case Binary::shr: return binary_of<Binary::shr>(s);
    }
    return nullptr;
}

template <Compare K>
OpFn compare_of(Scalar s, Scalar result, bool vector) {
    const bool wide = bytes_of(result) == 8;
#define F(T)                                                                                                   \
    vector ? (wide ? &op_compare<T, K, std::int64_t, true> : &op_compare<T, K, std::int32_t, true>)             \
           : (wide ? &op_compare<T, K, std::int64_t, false> : &op_compare<T, K, std::int32_t, false>)
    FIGGEN_BY_TYPE(s, F);
#undef F
}
OpFn compare(Compare k, Scalar s, Scalar result, bool vector) {
    switch (k) {
    case Compare::eq: return compare_of<Compare::eq>(s, result, vector);
    case Compare::ne: return compare_of<Compare::ne>(s, result, vector);
    case Compare::lt: return compare_of<Compare::lt>(s, result, vector);
    case Compare::gt: return compare_of<Compare::gt>(s, result, vector);
    case Compare::le: return compare_of<Compare::le>(s, result, vector);
    case Compare::ge: return compare_of<Compare::ge>(s, result, vector);
    }
    return nullptr;
}

template <Math1 M>
OpFn math1_of(Scalar s, bool vector) {
    if constexpr (M == Math1::iabs) {
        switch (s) {
        case Scalar::b:
        case Scalar::i32: return &op_math1<std::int32_t, M, false>;
        case Scalar::u32: return &op_math1<std::uint32_t, M, false>;
        case Scalar::i64: return &op_math1<std::int64_t, M, false>;
        case Scalar::u64: return &op_math1<std::uint64_t, M, false>;
        default: return nullptr;
        }
    } else {
        if (s == Scalar::f32) return vector ? &op_math1<float, M, true> : &op_math1<float, M, false>;
        if (s == Scalar::f64) return vector ? &op_math1<double, M, true> : &op_math1<double, M, false>;
        return nullptr;
    }
}
OpFn math1(Math1 m, Scalar s, bool vector) {
    switch (m) {
#define C(X) \
    case Math1::X: return math1_of<Math1::X>(s, vector);
        C(sqrt) C(rsqrt) C(cbrt) C(exp) C(exp2) C(exp10) C(expm1) C(log) C(log2) C(log10) C(log1p) C(sin) C(cos)
        C(tan) C(asin) C(acos) C(atan) C(sinh) C(cosh) C(tanh) C(asinh) C(acosh) C(atanh) C(fabs) C(floor) C(ceil)
        C(round) C(trunc) C(rint) C(sign) C(erf) C(erfc) C(tgamma) C(lgamma) C(iabs) C(isnan) C(isinf) C(isfinite)
#undef C
    }
    return nullptr;
}

template <Math2 M>
OpFn math2_of(Scalar s, bool vector) {
    if constexpr (M == Math2::min || M == Math2::max) {
#define F(T) &op_math2<T, M, false>
        FIGGEN_BY_TYPE(s, F);
#undef F
    } else {
        if (s == Scalar::f32) return vector ? &op_math2<float, M, true> : &op_math2<float, M, false>;
        if (s == Scalar::f64) return vector ? &op_math2<double, M, true> : &op_math2<double, M, false>;
        return nullptr;
    }
}
OpFn math2(Math2 m, Scalar s, bool vector) {
    switch (m) {
#define C(X) \
    case Math2::X: return math2_of<Math2::X>(s, vector);
        C(pow) C(atan2) C(hypot) C(fmod) C(fmin) C(fmax) C(min) C(max) C(step) C(copysign) C(fdim) C(remainder)
        C(powr) C(isless) C(isgreater) C(islessequal) C(isgreaterequal) C(isequal) C(isnotequal)
#undef C
    }
    return nullptr;
}

template <Math3 M>
OpFn math3_of(Scalar s) {
    if constexpr (M == Math3::clamp) {
#define F(T) &op_math3<T, M>
        FIGGEN_BY_TYPE(s, F);
#undef F
    } else {
        if (s == Scalar::f32) return &op_math3<float, M>;
        if (s == Scalar::f64) return &op_math3<double, M>;
        return nullptr;
    }
}
OpFn math3(Math3 m, Scalar s) {
    switch (m) {
    case Math3::clamp: return math3_of<Math3::clamp>(s);
    case Math3::mix: return math3_of<Math3::mix>(s);
    case Math3::fma: return math3_of<Math3::fma>(s);
    case Math3::mad: return math3_of<Math3::mad>(s);
    case Math3::smoothstep: return math3_of<Math3::smoothstep>(s);
    }
    return nullptr;
}

OpFn select(Scalar s) {
#define F(T) &op_select<T>
    FIGGEN_BY_TYPE(s, F);
#undef F
}
OpFn to_mask(Scalar s) {
#define F(T) &op_to_mask<T>
    FIGGEN_BY_TYPE(s, F);
#undef F
}
OpFn sign_mask(Scalar s) {
#define F(T) &op_sign_mask<T>
    FIGGEN_BY_TYPE(s, F);
#undef F
}
OpFn from_mask() { return &op_from_mask; }
OpFn mask_and() { return &op_mask_and; }
OpFn mask_or() { return &op_mask_or; }
OpFn mask_not() { return &op_mask_not; }
OpFn check_index() { return &op_check_index; }
OpFn buffer_load(Scalar s) {
#define F(T) &op_buffer_load<T>
    FIGGEN_BY_TYPE(s, F);
#undef F
}
OpFn buffer_store(Scalar s) {
#define F(T) &op_buffer_store<T>
    FIGGEN_BY_TYPE(s, F);
#undef F
}
OpFn array_load(Scalar s) {
#define F(T) &op_array_load<T>
    FIGGEN_BY_TYPE(s, F);
#undef F
}
OpFn array_store(Scalar s) {
#define F(T) &op_array_store<T>
    FIGGEN_BY_TYPE(s, F);
#undef F
}
OpFn global_size() { return &op_global_size; }
OpFn if_node() { return &op_if; }
OpFn loop_node() { return &op_loop; }
OpFn switch_node() { return &op_switch; }
OpFn guard_node() { return &op_guard; }
OpFn jump() { return &op_jump; }
OpFn call_node() { return &op_call; }

}  // namespace ops

Lanes::Lanes(const Compiled& program) : ctx_(new Ctx) {
    ctx_->p = &program;
    const auto regs = static_cast<std::size_t>(std::max(program.registers, 1));
    ctx_->reg_storage.reset(new std::uint64_t[regs * lanes]());
    ctx_->uni_storage.reset(new std::uint8_t[regs]());
    ctx_->mask_storage.reset(new std::uint8_t[static_cast<std::size_t>(std::max(program.masks, 2)) * lanes]());
    ctx_->regs = ctx_->reg_storage.get();
    ctx_->uni = ctx_->uni_storage.get();
    ctx_->masks = ctx_->mask_storage.get();
}

Lanes::~Lanes() { delete ctx_; }

long long Lanes::executed() const { return ctx_->executed; }

bool Lanes::run(const Launch& launch, long long first, int count, Failure& failure) {
    Ctx& c = *ctx_;
    const Compiled& p = *c.p;
    c.launch = &launch;
    c.first = first;
    c.failure = &failure;
    c.n = count;
    c.stop = false;
    std::memset(c.trips, 0, sizeof c.trips);
    std::memset(mreg(c, 0), 0, lanes);
    std::uint8_t* all = mreg(c, 1);
    std::memset(all, 0, lanes);
    std::memset(all, 1, static_cast<std::size_t>(count));
    // get_global_id of each lane
    const long long gx = p.global[0], gy = p.global[1];
    for (int k = 0; k < 3; ++k) {
        std::uint64_t* id = reg<std::uint64_t>(c, p.id_registers[k]);
        bool same = true;
        for (int l = 0; l < count; ++l) {
            const long long w = first + l;
            const long long v = k == 0 ? w % gx : k == 1 ? (w / gx) % gy : w / (gx * gy);
            id[l] = static_cast<std::uint64_t>(v);
            same = same && id[l] == id[0];
        }
        c.uni[p.id_registers[k]] = same;
    }
    set_mask(c, 1);
    exec(c, 0);
    if (!c.stop) {
        set_mask(c, 1);
        exec(c, 1);
    }
    return !c.stop;
}

}  // namespace sim::kernel
