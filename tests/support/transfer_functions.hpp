#pragma once
// Transfer functions shared by the pre-integration tests.
#include "core/volume/optics/transfer_function.hpp"

namespace weft::test {

// A sharp, dense peak at s = 0.5, a step at s = 0.7, constant below 0.1 and above 0.9.
inline TransferFunction peakedTf() {
    return TransferFunction(0, 1, {{0.1, {0.2, 0.3, 1.0}, 0.0},
                                   {0.45, {0.2, 0.3, 1.0}, 0.05},
                                   {0.5, {1.0, 0.2, 0.1}, 40.0},
                                   {0.55, {1.0, 1.0, 0.2}, 0.05},
                                   {0.7, {0.0, 1.0, 0.0}, 2.0},
                                   {0.7, {1.0, 0.0, 1.0}, 0.3},
                                   {0.9, {0.5, 0.5, 0.5}, 1.0}});
}

}  // namespace weft::test
