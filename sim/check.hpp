#pragma once
// Parameter checks shared by the models. Each throws ParameterError naming
// the parameter, the bad value and what is allowed.

#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/grid.hpp"

namespace sim {

// A parameter a model refuses. what(): "name = value is not allowed: allowed".
struct ParameterError : std::invalid_argument {
    ParameterError(std::string name, std::string value, std::string allowed);
    std::string name;     // the model's name for it, e.g. "angle_degrees"
    std::string value;    // as shown in the message, short ("1e+308")
    std::string allowed;  // e.g. "a number from 0 to 0.25"
};

// A number as messages show it: at most 6 significant digits ("1e+308", "0.25").
std::string shown(double value);

// `why`, when given, follows the range in brackets: where the bound comes from.
void require_number(const char* name, double value, double low, double high, const char* why = nullptr);
// An explicit starting field must be n x n and finite; `name` is e.g. "A".
void require_square_field(const char* name, const Grid<double>& field, int n);
void require_integer(const char* name, long long value, long long low, long long high);

// A model's health: throws std::runtime_error naming `model` and `step` if
// any cell is NaN or infinite, or farther than `bound` from 0. A run that
// went unstable never reaches an image.
void require_finite(const Grid<double>& field, const std::string& model, int step,
                    double bound = std::numeric_limits<double>::infinity());

// While a RangeLog lives on a thread, require_number and require_integer
// note each name with its allowed range there: `figgen describe` lists the
// ranges the models really check.
struct CheckedRange {
    std::string name;
    double low, high;
    bool integer;
    std::string why;
};
class RangeLog {
public:
    RangeLog();
    ~RangeLog();
    RangeLog(const RangeLog&) = delete;
    RangeLog& operator=(const RangeLog&) = delete;
    const std::vector<CheckedRange>& ranges() const { return ranges_; }
    static void note(CheckedRange range);  // no-op without a log

private:
    std::vector<CheckedRange> ranges_;
    RangeLog* outer_;
};

}  // namespace sim
