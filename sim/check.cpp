#include "sim/check.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "sim/boundary.hpp"

namespace sim {

namespace {
thread_local RangeLog* current_log = nullptr;
}  // namespace

RangeLog::RangeLog() : outer_(current_log) { current_log = this; }
RangeLog::~RangeLog() { current_log = outer_; }
void RangeLog::note(CheckedRange range) {
    if (current_log) current_log->ranges_.push_back(std::move(range));
}

void require_number(const char* name, double value, double low, double high, const char* why) {
    RangeLog::note({name, low, high, false, why ? why : ""});
    if (std::isfinite(value) && value >= low && value <= high) return;
    std::ostringstream message;
    message << name << " = " << value << " is not allowed: " << name << " must be a number from " << low << " to "
            << high;
    if (why) message << " (" << why << ")";
    throw std::invalid_argument(message.str());
}

void require_integer(const char* name, long long value, long long low, long long high) {
    RangeLog::note({name, double(low), double(high), true, ""});
    if (value >= low && value <= high) return;
    std::ostringstream message;
    message << name << " = " << value << " is not allowed: " << name << " must be an integer from " << low << " to "
            << high;
    throw std::invalid_argument(message.str());
}

void require_square_field(const char* name, const Grid<double>& g, int n) {
    if (g.rows() != n || g.cols() != n)
        throw std::invalid_argument(std::string("initial ") + name + " is " + std::to_string(g.rows()) + "x" +
                                    std::to_string(g.cols()) + ", not n x n = " + std::to_string(n) + "x" +
                                    std::to_string(n));
    for (double v : g.cells())
        if (!std::isfinite(v))
            throw std::invalid_argument(std::string("initial ") + name + " holds a non-finite value");
}

Boundary parse_boundary(std::string_view text) {
    if (text == "zero") return Boundary::zero;
    if (text == "wrap") return Boundary::wrap;
    throw std::invalid_argument("boundary = \"" + std::string(text) + "\" is not allowed: use \"zero\" or \"wrap\"");
}

}  // namespace sim
