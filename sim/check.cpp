#include "sim/check.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace sim {

namespace {
thread_local RangeLog* current_log = nullptr;
}  // namespace

RangeLog::RangeLog() : outer_(current_log) { current_log = this; }
RangeLog::~RangeLog() { current_log = outer_; }
void RangeLog::note(CheckedRange range) {
    if (current_log) current_log->ranges_.push_back(std::move(range));
}

ParameterError::ParameterError(std::string name_, std::string value_, std::string allowed_)
    : std::invalid_argument(name_ + " = " + value_ + " is not allowed: " + allowed_),
      name(std::move(name_)),
      value(std::move(value_)),
      allowed(std::move(allowed_)) {}

std::string shown(double value) {
    std::ostringstream text;
    text << value;  // the stream's default: %g with 6 digits
    return text.str();
}

void require_number(const char* name, double value, double low, double high, const char* why) {
    RangeLog::note({name, low, high, false, why ? why : ""});
    if (std::isfinite(value) && value >= low && value <= high) return;
    std::string allowed = "a number from " + shown(low) + " to " + shown(high);
    if (why) allowed += std::string(" (") + why + ")";
    throw ParameterError(name, shown(value), allowed);
}

void require_integer(const char* name, long long value, long long low, long long high) {
    RangeLog::note({name, double(low), double(high), true, ""});
    if (value >= low && value <= high) return;
    throw ParameterError(name, std::to_string(value),
                         "an integer from " + std::to_string(low) + " to " + std::to_string(high));
}

void require_finite(const Grid<double>& field, const std::string& model, int step, double bound) {
    for (double v : field.cells()) {
        if (!std::isfinite(v))
            throw std::runtime_error(model + " went numerically unstable at step " + std::to_string(step) +
                                     " (non-finite values); no image written");
        if (std::abs(v) > bound) {
            char detail[96];
            std::snprintf(detail, sizeof detail, " (a value of %g, beyond %g)", v, bound);
            throw std::runtime_error(model + " went numerically unstable at step " + std::to_string(step) + detail +
                                     "; no image written");
        }
    }
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

}  // namespace sim
