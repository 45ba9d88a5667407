// tests/compile/impl.cpp - the implementation compiled as C++ next to the
// standard library, as a C++ program would include it.  Compiled with
// -std=c++11 and -std=c++17, -Wall -Wextra -pedantic -Werror, g++ and clang++.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#define MANYLODS_IMPLEMENTATION
#include "../../manylods.h"
#include "smoke.h"

int main()
{
    // std::min, std::max and numeric_limits<>::max() still work: the header
    // defined no macro that breaks them.
    std::vector<mlod_view> views(3);
    std::vector<float> values(1, std::numeric_limits<float>::max());
    uint32_t checksum = 0;
    int failed = smoke_run("impl.cpp", nullptr, &checksum);
    values.push_back(std::min(1.0f, std::max(0.0f, std::sqrt(2.0f))));
    if (views.size() != 3 || values.size() != 2 || values[1] != 1.0f) failed = 1;
    if (std::string(mlod_result_name(MLOD_OK)).empty()) failed = 1;
    return failed;
}
