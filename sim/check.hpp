#pragma once
// Parameter checks shared by the models. Each throws std::invalid_argument
// with one line naming the parameter, the bad value and what is allowed.

#include <string>

namespace sim {

void require_number(const char* name, double value, double low, double high);
void require_integer(const char* name, long long value, long long low, long long high);

}  // namespace sim
